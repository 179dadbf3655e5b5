#pragma once
// Step 5b of the mesh stage (mesh_output.hpp): vertices inside diagonals of a region's triangles.
#include <array>
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "core/output/output_vertices.hpp"

namespace ember::core {
class VertexIndex;
}

namespace ember::core {

/// Step 5b for one region's triangles (a triangulation of a plane region):
/// every vertex that some output triangle uses (`used`, per vertex id) and
/// that lies strictly inside a diagonal (an edge two of the triangles share)
/// is inserted, splitting both triangles. Such a vertex is a point where
/// another part of the result touches the region's interior. (Vertices no
/// triangle uses, such as the inner corners of merged pieces, are skipped.)
/// Returns the number of vertices inserted (0: `tris` unchanged).
std::size_t split_diagonals(const Plane& plane, const OutputVertices& verts, const VertexIndex& index,
                            const std::vector<char>& used, std::vector<std::array<std::uint32_t, 3>>& tris);

}  // namespace ember::core
