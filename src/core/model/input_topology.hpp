#pragma once
// What the input stage and the proof know about the input triangles, for the
// output stage's weld and T-junction search.
#include <array>
#include <cstdint>
#include <span>
#include <vector>

namespace ember::core {

/// What the set-up and the proof know about the input triangles (by id).
/// Their welded grid vertex ids, made global: corner k of triangle t of
/// operand o is vertex operand_base[o] + by_triangle[t][k]. Equal ids are
/// equal points; equal points of different operands have different ids.
struct InputTopology {
  std::span<const std::array<std::uint32_t, 3>> by_triangle;
  std::vector<std::uint32_t> operand_base;  ///< one per operand, then the total
  /// Bit k of triangle t: its edge k is a manifold edge of its operand
  /// (EdgeMatching::manifold). Empty: unknown.
  std::span<const std::uint8_t> manifold_edges;
  /// Per operand: solid (proven or promised; no two of its triangles meet
  /// beyond a shared vertex or edge). Empty: unknown.
  std::vector<char> solid;
};

}  // namespace ember::core
