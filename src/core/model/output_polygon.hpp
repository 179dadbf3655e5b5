#pragma once
// The pieces every route emits and the output stage turns into a mesh.
#include <array>
#include <cstdint>

#include "core/model/soup.hpp"

namespace ember::core {

/// A piece of an input triangle that lies on the result's surface, in one of
/// three forms (48 bytes; most output pieces are the first two):
///  * unbuilt: the whole input triangle (`corners`), emitted by an early-out
///    or a leaf that did not cut it, or put back together by
///    merge_whole_triangles;
///  * by path (`path` set): the triangle's whole subdivision piece in the
///    box that emitted it, i.e. the triangle clipped by that box's splits in
///    their order (expand_path_pieces rebuilds it exactly). Most such pieces
///    merge back into whole triangles, so their vertices are never stored;
///  * explicit: the vertices of a piece a leaf cut or trimmed.
/// The support plane is always the triangle's (support_of).
struct OutputPolygon {
  PolygonBuffer<Point> vertices;  ///< explicit corners (counter-clockwise around the support); else empty
  const std::array<IntPoint, 3>* corners =
      nullptr;           ///< the source triangle's grid corners (GridTriangles::corners[id])
  std::uint32_t id = 0;  ///< source polygon (input triangle) id
  std::uint32_t operand = 0;
  /// By path: an index into the solve's paths (SolveOutput); kNoPath otherwise.
  std::uint32_t path = kNoPath;
  /// How many subdivision splits made the piece (SoupPolygon::splits).
  std::uint8_t splits = 0;
  // Bit-fields keep the struct at 48 bytes with the layer range below.
  bool flip : 1 = false;  ///< emit with reversed orientation (in-out transition)
  /// The polygon is the whole subdivision piece its source triangle had in
  /// the box that emitted it (no leaf cut or trimmed it).
  bool whole_piece : 1 = false;
  /// Nothing else in the output can touch it but along its own edges and at
  /// its corners: an unbuilt triangle whose three edges it shares with whole
  /// triangles of its operand that no other operand comes near (the solid
  /// path's interior triangles, solid_route.hpp). No vertex lies inside its
  /// edges and none of its corners inside another polygon's edge, so the
  /// mesh stage passes it through as it is.
  bool settled : 1 = false;
  /// Layer mode (SolveContext::layers): the piece bounds the layers k with
  /// layer_lo < k <= layer_hi, the counts of operands containing the points
  /// on its two sides; the side with more is inside those layers.
  std::uint8_t layer_lo = 0, layer_hi = 0;

  static constexpr std::uint32_t kNoPath = UINT32_MAX;
  /// The most operands layer mode can count (layer_lo, layer_hi).
  static constexpr std::size_t kMaxLayers = 255;
};
static_assert(sizeof(OutputPolygon) <= 48, "output pieces are the largest buffer of a solve: keep them small");
static_assert(OutputPolygon::kMaxLayers <= UINT8_MAX, "layer_lo and layer_hi count operands in 8 bits");

/// The whole input triangle, without stored vertices.
inline bool unbuilt(const OutputPolygon& p) { return p.vertices.empty() && p.path == OutputPolygon::kNoPath; }
/// How many corners p has (3 for an unbuilt triangle; a path piece must be expanded first).
inline std::size_t corner_count(const OutputPolygon& p) { return unbuilt(p) ? 3 : p.vertices.size(); }
/// The support plane of p: its input triangle's.
inline Plane support_of(const OutputPolygon& p) {
  const std::array<IntPoint, 3>& c = *p.corners;
  return *supporting_plane(c[0], c[1], c[2]);  // an output triangle has area
}

}  // namespace ember::core
