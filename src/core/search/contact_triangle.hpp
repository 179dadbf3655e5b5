#pragma once
// A grid triangle as the contact tests take it: corners by reference, ids, normal.
#include <array>
#include <cstdint>

#include "geometry/plane.hpp"

namespace ember::core {

/// A grid triangle prepared for the contact test: where its corners are,
/// their welded ids (equal iff equal positions, within the triangles
/// compared) and its normal (p1 - p0) x (p2 - p0) (grid_normal), computed
/// once per triangle instead of once per pair.
/// The corners are referred to, not copied: the proof holds one entry per
/// triangle of the operand it proves, a copy (72 bytes) would more than
/// double the entry, and at many threads every operand is proven at once.
/// The caller keeps the corners alive (the proof: GridTriangles::corners).
struct ContactTriangle {
  const std::array<IntPoint, 3>* corners = nullptr;
  std::array<std::int64_t, 3> n;
  std::array<std::uint32_t, 3> id;
  /// Bit k: the star of corner k's vertex is certified embedded
  /// (vertex_stars.hpp), so triangles sharing that vertex never meet
  /// improperly. 0 (nothing certified) unless certify_embedded_stars set it.
  std::uint8_t embedded = 0;
  const std::array<IntPoint, 3>& p() const { return *corners; }
};
static_assert(sizeof(ContactTriangle) <= 48, "ContactTriangle: the proof's per-triangle entry");
/// The contact triangle of the corners `p`, which must outlive it.
ContactTriangle contact_triangle(const std::array<IntPoint, 3>& p, const std::array<std::uint32_t, 3>& ids);
/// The same with p's grid normal given (GridTriangles::normals).
inline ContactTriangle contact_triangle(const std::array<IntPoint, 3>& p, const std::array<std::int64_t, 3>& n,
                                        const std::array<std::uint32_t, 3>& ids) {
  return {&p, n, ids, 0};
}
/// The triangle points at `p`: a temporary would dangle.
ContactTriangle contact_triangle(std::array<IntPoint, 3>&& p, const std::array<std::uint32_t, 3>& ids) = delete;

}  // namespace ember::core
