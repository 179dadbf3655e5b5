#pragma once
// The Boolean's input stage after quantization (grid_input.hpp): validation
// of the caller's meshes, closedness, and the grid triangles the core solves. Every
// step is parallel and its result independent of scheduling.
#include <cstdint>
#include <span>
#include <vector>

#include "core/input/grid_input.hpp"
#include "core/model/soup.hpp"
#include "core/model/grid_triangles.hpp"
#include "core/support/fill_vector.hpp"
#include "ember/mesh.hpp"

namespace ember::core {

/// Throws ember::Error naming the first problem (lowest operand, then lowest
/// face or vertex): face offsets that do not frame `indices`, faces with
/// fewer than 3 corners, vertex indices out of range, non-finite coordinates.
void validate_operands(std::span<const Mesh> operands);

/// The input's edges matched on the welded grid positions, degenerate
/// triangles included (the surface the core actually sees).
struct EdgeMatching {
  /// Per operand, the undirected edges whose uses in one direction are not
  /// matched by uses in the other. 0 = closed.
  std::vector<std::size_t> open;
  /// Per triangle (GridInput order): bit k set when its edge k (corner k to
  /// corner k + 1) is used by exactly one other triangle of its operand, in
  /// the opposite direction (a manifold edge; the mesh stage's T-junction
  /// search relies on it, mesh_output.hpp).
  std::vector<std::uint8_t> manifold;
  /// Per triangle (GridInput order), per edge k with its manifold bit set:
  /// the other triangle using it (GridInput index); kNoNeighbor otherwise.
  FillVector<std::array<std::uint32_t, 3>> partner;
};
EdgeMatching match_edges(const GridInput& gi);

/// The non-degenerate grid triangles, numbered in input order (the total
/// order of coplanar overlaps): sources[id] their origin, grid.corners by id
/// (the root soup's unbuilt triangles point into it, so it must outlive the
/// soup and the solve's output; the solid proof, the solid path and
/// merge_whole_triangles read it too), grid.vertex_ids by id (the solid
/// proof's edge matching, the mesh stage's weld), grid.manifold_edges and
/// grid.neighbors by id (from `edges`, in GridInput order), grid.normals by
/// id, and each operand's range of ids. When no triangle is dropped, gi's
/// corners, vertex ids and normals are moved out of it (left empty). The
/// root soup itself is built from them where it is needed (root_problem.hpp).
struct InputTriangles {
  FillVector<Provenance> sources;
  GridTriangles grid;
  /// Operand o's triangles are ids [operand_begin[o], operand_begin[o + 1]).
  std::vector<std::uint32_t> operand_begin;
  std::size_t dropped_degenerate = 0;
};
InputTriangles build_grid_triangles(GridInput& gi, const EdgeMatching& edges);

}  // namespace ember::core
