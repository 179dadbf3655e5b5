#pragma once
// Step 4 of the mesh stage (mesh_output.hpp): exact ear clipping of each region.
#include <array>
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "core/output/output_vertices.hpp"
#include "core/output/regions.hpp"

namespace ember::core {

/// Step 4 for one region: appends triangles (counter-clockwise around the
/// region's outward normal). False if the region's loops are not a polygon
/// with holes that ear clipping can handle; nothing is appended then.
bool triangulate_region(const Regions& regions, std::uint32_t region, const OutputVertices& verts,
                        std::vector<std::array<std::uint32_t, 3>>& out);

/// Loops longer than this find the vertices an ear must not hold through a
/// grid (loop_grid.hpp) instead of walking round the loop for each ear.
inline constexpr std::size_t kEarGridLoop = 64;

/// Ear-clips one cyclic polygon (no holes) given as vertex ids, counter-
/// clockwise around `plane`. False if no valid ear can be found.
/// `grid_from`: the loop length from which the grid is used (tests compare
/// both ways; the triangles are the same).
bool triangulate_loop(std::span<const std::uint32_t> loop, const Plane& plane, const OutputVertices& verts,
                      std::vector<std::array<std::uint32_t, 3>>& out, std::size_t grid_from = kEarGridLoop + 1);

/// Ear-clips a polygon with holes: `outer` counter-clockwise around `plane`,
/// each hole clockwise, joined to it by bridges first. False if a bridge or
/// an ear cannot be found.
bool triangulate_with_holes(std::vector<std::uint32_t> outer, std::vector<std::vector<std::uint32_t>> holes,
                            const Plane& plane, const OutputVertices& verts,
                            std::vector<std::array<std::uint32_t, 3>>& out);

/// +1 if the loop runs counter-clockwise around `plane`, -1 clockwise, 0 if
/// its turn at its lexicographically smallest vertex is straight.
int loop_orientation_in_plane(const std::vector<std::uint32_t>& loop, const Plane& plane, const OutputVertices& verts);

/// Whether vertex x (on `plane`) lies inside the loop (1), outside (0) or
/// on it (-1), exactly: a ray's crossings in the projection along the
/// plane's dominant axis.
int locate_in_loop(const std::vector<std::uint32_t>& loop, std::uint32_t x, const Plane& plane,
                   const OutputVertices& verts);

}  // namespace ember::core
