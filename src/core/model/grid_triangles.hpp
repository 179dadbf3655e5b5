#pragma once
// The grid triangles every stage after the set-up reads, indexed by id.
#include <array>
#include <cstdint>

#include "core/support/fill_vector.hpp"
#include "geometry/plane.hpp"

namespace ember::core {

inline constexpr std::uint32_t kNoNeighbor = UINT32_MAX;

/// The grid triangles behind the soup's polygons, indexed by polygon id.
/// FillVectors (fill_vector.hpp): build_grid_triangles sizes them, then writes every
/// entry in parallel.
struct GridTriangles {
  FillVector<std::array<IntPoint, 3>> corners;
  /// grid_normal of each triangle's corners (non-zero: degenerate
  /// triangles are not kept), stored for the hot loops that need it (the
  /// proof's contact tests, the partner search, the pair chords): 24 bytes
  /// per triangle, computed once here, where each of those loops would
  /// otherwise recompute it for every pair it tests.
  FillVector<std::array<std::int64_t, 3>> normals;
  /// Welded vertex ids (edge_matching.hpp): within one operand, equal ids iff equal positions.
  FillVector<std::array<std::uint32_t, 3>> vertex_ids;
  /// Bit k: edge k is a manifold edge of its operand (EdgeMatching::manifold).
  FillVector<std::uint8_t> manifold_edges;
  /// Across manifold edge k: the other triangle's id (kNoNeighbor: none, or
  /// the edge is not manifold, or the other triangle is degenerate).
  FillVector<std::array<std::uint32_t, 3>> neighbors;
};

}  // namespace ember::core
