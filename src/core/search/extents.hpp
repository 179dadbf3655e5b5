#pragma once
// Extents of grid triangles along fixed directions, a conservative separation test.
#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>

#include "geometry/bounds.hpp"
#include "geometry/plane.hpp"

namespace ember::core {

/// A triangle's extent along D directions: lowest projections, then highest
/// (diagonal_extent; frame_extent in leaf_frame_extents.hpp).
template <std::size_t D>
struct ProjectedExtent {
  std::array<std::int64_t, D> lo, hi;
};

/// The two extents do not overlap along some direction. Where each bounds
/// its triangle's projections (exactly, or widened), the triangles are
/// disjoint: a common point would project into both.
template <std::size_t D>
bool extents_apart(const ProjectedExtent<D>& a, const ProjectedExtent<D>& b) {
  for (std::size_t k = 0; k < D; ++k)
    if (a.hi[k] < b.lo[k] || b.hi[k] < a.lo[k]) return true;
  return false;
}

/// A triangle's extent along the four diagonals (1,1,1), (1,1,-1), (1,-1,1),
/// (-1,1,1). With the box it bounds the triangle by 14 planes; long slivers
/// across the axes, whose boxes overlap many others', are told apart by it.
using DiagonalExtent = ProjectedExtent<4>;
inline DiagonalExtent diagonal_extent(const std::array<IntPoint, 3>& p) {
  // |coordinate| <= 2^25: a projection is below 3 * 2^25 in magnitude.
  static_assert(3 * kCoordLimit < (std::int64_t{1} << 62), "diagonal projections must fit int64");
  const auto project = [](const IntPoint& q) {
    const std::int64_t s = q.x + q.y, d = q.x - q.y;
    return std::array<std::int64_t, 4>{s + q.z, s - q.z, d + q.z, q.z - d};
  };
  const std::array<std::int64_t, 4> a = project(p[0]), b = project(p[1]), c = project(p[2]);
  DiagonalExtent e;
  for (int k = 0; k < 4; ++k) {
    e.lo[k] = std::min({a[k], b[k], c[k]});
    e.hi[k] = std::max({a[k], b[k], c[k]});
  }
  return e;
}

/// The two extents do not overlap along some diagonal: the triangles are
/// disjoint (exact: integer projections), so they do not meet at all.
inline bool diagonally_apart(const DiagonalExtent& a, const DiagonalExtent& b) { return extents_apart(a, b); }

}  // namespace ember::core
