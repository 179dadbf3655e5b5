#pragma once
// Per operand, its triangles' tree (triangle_tree.hpp) and the diagonal
// extents of its leaves (leaf_diagonals.hpp): built once, read by the solid
// proof's contact search (each operand against itself), the solid path's
// partner search (pairs of operands) and its traces.
#include <algorithm>
#include <cstdint>
#include <span>
#include <vector>

#include "core/leaf_diagonals.hpp"
#include "core/principal_frame.hpp"
#include "core/triangle_tree.hpp"

namespace ember::core {

/// Operand o's triangles are ids [begin[o], begin[o + 1]); tree[o] holds
/// them (item i is id begin[o] + i) and diagonals[o] their leaves' extents.
struct OperandTrees {
  std::vector<std::uint32_t> begin;
  std::vector<TriangleTree> tree;
  std::vector<LeafDiagonals> diagonals;
  /// Frames sampled before the searches that use them (combined_search.cpp):
  /// per operand its sliver_frame (or none sampled: empty), and with two
  /// operands their partner_frame.
  std::vector<SampledFrame> sliver;
  SampledFrame partner;
  /// The operand whose range holds triangle `id` (< begin.back()).
  std::uint32_t operand_of(std::uint32_t id) const {
    return static_cast<std::uint32_t>(std::upper_bound(begin.begin(), begin.end(), id) - begin.begin() - 1);
  }
};

/// The trees of every operand's triangles: operand o's are triangles
/// [begin[o], begin[o + 1]) with corners `corners`, with their diagonals
/// unless `diagonals` is false (add_diagonals). `common_cells`: key them
/// over the operands' common bounds where that is as fine as over each
/// one's own (TriangleTree::same_cell_size), so that they merge into one
/// tree (TriangleTree::merged). Parallel (oneTBB).
OperandTrees build_operand_trees(std::vector<std::uint32_t> begin, std::span<const std::array<IntPoint, 3>> corners,
                                 bool diagonals = true, bool common_cells = false);

/// The leaves' diagonal extents of trees built without them.
void add_diagonals(OperandTrees& trees, std::span<const std::array<IntPoint, 3>> corners);

}  // namespace ember::core
