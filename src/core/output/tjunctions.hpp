#pragma once
// Step 2 of the mesh stage (mesh_output.hpp): vertices inserted into the edges they lie in.
#include <array>
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "core/output/output_vertices.hpp"

namespace ember::core {

class VertexIndex;  // core/mesh/vertex_index.hpp

/// Every output vertex, bucketed for searches along segments. With two
/// operands of which one is solid and `topology`'s manifold edges, each
/// cell is ordered by which operands' polygons use the vertex, so that step
/// 2 can search an edge between two whole triangles of a solid operand for
/// the other operand's vertices alone (tjunctions.cpp, whole_solid_edge):
/// far from the other operand those parts of the cells are empty.
VertexIndex index_output_vertices(std::span<const OutputPolygon> polys, const OutputVertices& verts,
                                  const InputTopology* topology = nullptr);

/// The corner edges (corner c runs from corners.ids[c] to the next corner of
/// its polygon) grouped by undirected id pair: every edge of a pair is the
/// same segment, so it is searched once.
struct EdgePairs {
  static constexpr std::uint32_t kNoRun = UINT32_MAX;
  std::vector<std::uint32_t> corner;     ///< corners sorted by (pair, corner)
  std::vector<std::uint32_t> run_begin;  ///< pair r owns corner[run_begin[r] .. run_begin[r+1])
  std::vector<std::uint32_t> run_of;     ///< per corner: its pair (kNoRun: a settled polygon's)
  std::vector<std::uint32_t> poly_of;    ///< per corner: its polygon
};
/// With `polys`, the corners of settled polygons (OutputPolygon::settled)
/// are left out: their edges need no search and join nothing.
EdgePairs group_edges_by_pair(const Cycles& corners, std::span<const OutputPolygon> polys = {});

/// Step 2. Per polygon (unflipped order): corners with every vertex that lies
/// in the open interior of an edge inserted in order along it. Counts the
/// insertions in `inserted`. `pairs` groups verts.corners. `index` must have
/// been built with the same `topology`.
Cycles insert_tjunction_vertices(std::span<const OutputPolygon> polys, const OutputVertices& verts,
                                 const VertexIndex& index, const EdgePairs& pairs, std::size_t& inserted,
                                 const InputTopology* topology = nullptr);

}  // namespace ember::core
