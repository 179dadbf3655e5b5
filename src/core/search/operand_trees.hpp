#pragma once
// Per operand, its triangles' tree (triangle_tree.hpp) and the diagonal
// extents of its leaves (leaf_diagonals.hpp): built once, read by the solid
// proof's contact search (each operand against itself), the solid path's
// partner search (pairs of operands) and its traces.
#include <algorithm>
#include <cstdint>
#include <span>
#include <vector>

#include "core/search/leaf_diagonals.hpp"
#include "core/search/triangle_tree.hpp"

namespace ember::core {

/// Operand o's triangles are ids [begin[o], begin[o + 1]); tree[o] holds
/// them (item i is id begin[o] + i) and diagonals[o] their leaves' extents.
struct OperandTrees {
  std::vector<std::uint32_t> begin;
  std::vector<TriangleTree> tree;
  std::vector<LeafDiagonals> diagonals;
  /// The operand whose range holds triangle `id` (< begin.back()).
  std::uint32_t operand_of(std::uint32_t id) const {
    return static_cast<std::uint32_t>(std::upper_bound(begin.begin(), begin.end(), id) - begin.begin() - 1);
  }
};

/// The trees of every operand's triangles: operand o's are triangles
/// [begin[o], begin[o + 1]) with corners `corners`. Parallel (oneTBB).
OperandTrees build_operand_trees(std::vector<std::uint32_t> begin, std::span<const std::array<IntPoint, 3>> corners);

}  // namespace ember::core
