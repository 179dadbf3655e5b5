#pragma once
// Step 2b of the mesh stage (mesh_output.hpp): whole triangles that leave it as they came.
#include <array>
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "core/output/output_vertices.hpp"
#include "core/output/tjunctions.hpp"

namespace ember::core {

/// Step 2b. Per polygon, 1 if it leaves the mesh stage as it came: a settled
/// polygon, or an unbuilt triangle (a whole input triangle) that gained no
/// vertex in step 2 and shares no edge with a piece of the same oriented
/// plane, so that step 3 would make it a region of its own and step 4 would
/// emit it unchanged.
/// Such triangles skip steps 3 and 4. `cycles` are step 2's.
std::vector<char> pass_through_triangles(std::span<const OutputPolygon> polys, const OutputVertices& verts,
                                         const EdgePairs& pairs, const Cycles& cycles);

}  // namespace ember::core
