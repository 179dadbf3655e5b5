#pragma once
// Splitting a convex polygon by a plane (paper Section 4.2.1, Fig. 6).
#include <cstdint>
#include <span>

#include "geometry/polygon.hpp"

namespace ember {

/// Where a polygon lies relative to a splitting plane.
enum class ClipSide {
  Negative,  ///< no vertex classifies > 0 (some < 0): the polygon is on the negative side
  Positive,  ///< no vertex classifies < 0 (some > 0)
  Both,      ///< vertices on both sides: the outputs hold the two parts
  On,        ///< every vertex lies on the plane
};

/// Decides the side from per-vertex signs (-1, 0, +1).
inline ClipSide clip_side(std::span<const std::int8_t> signs) {
  bool neg = false, pos = false;
  for (const std::int8_t s : signs) {
    neg |= s < 0;
    pos |= s > 0;
  }
  if (neg && pos) return ClipSide::Both;
  if (pos) return ClipSide::Positive;
  return neg ? ClipSide::Negative : ClipSide::On;
}

/// Splits `poly` by `split`. Returns Negative / Positive / On without touching the
/// outputs (the caller keeps `poly` as it is). Returns Both after filling
/// `negative_part` (the part where split <= 0) and `positive_part` (split >= 0):
///  * each part keeps the support plane and the convention of polygon.hpp
///    (edge i from vertex i to i+1, vertex i = support ∩ edges[i-1] ∩ edges[i],
///    interior on the negative side of every edge);
///  * the new edge is `split` in the negative part and `-split` in the positive part;
///  * each edge crossed from -1 to +1 gets one new vertex intersect(support, edge,
///    split), shared by both parts; vertices on the plane go to both parts, so each
///    part has exactly two vertices on the plane.
/// The outputs are cleared and refilled, so reusing them across calls reuses
/// their capacity (no allocation in steady state). `poly` must not alias an output.
ClipSide clip(const Polygon& poly, const Plane& split, Polygon& negative_part, Polygon& positive_part);

/// Same, with the vertex signs classify(poly.vertices[i], split) precomputed by
/// the caller (signs.size() == poly.size()).
ClipSide clip(const Polygon& poly, std::span<const std::int8_t> signs, const Plane& split, Polygon& negative_part,
              Polygon& positive_part);

}  // namespace ember
