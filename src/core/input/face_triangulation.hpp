#pragma once
// Exact triangulation of an input polygon on the integer grid.
//
// A fan from the first corner is right for convex faces, but the fan of a
// concave face has overlapping triangles: the winding numbers stay correct
// (the general path is exact for them), yet the solid proof sees a
// self-intersection. So faces with more than three corners are ear-clipped in
// the projection along the dominant axis of their Newell normal, with exact
// integer orientation tests.
#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "geometry/plane.hpp"

namespace ember::core {

/// Appends the corner-index triples (into `corners`) of a triangulation of
/// the polygon `corners` (grid positions, in order) to `out`. Ear clipping
/// when the projected polygon is simple enough for it; if no ear is found
/// (self-overlapping or non-planar faces) the fan is used, which still gives
/// the same winding numbers.
void triangulate_polygon(std::span<const IntPoint> corners, std::vector<std::array<std::uint32_t, 3>>& out);

}  // namespace ember::core
