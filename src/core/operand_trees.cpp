// Per-operand triangle trees and leaf diagonals (operand_trees.hpp).
#include "core/operand_trees.hpp"

#include <tbb/parallel_for.h>

namespace ember::core {

OperandTrees build_operand_trees(std::vector<std::uint32_t> begin, std::span<const std::array<IntPoint, 3>> corners,
                                 bool diagonals, bool common_cells) {
  OperandTrees t;
  t.begin = std::move(begin);
  const std::size_t operands = t.begin.size() - 1;
  t.tree.resize(operands);
  std::vector<std::vector<Box32>> boxes(operands);
  std::vector<Box32> bounds(operands);
  tbb::parallel_for(std::size_t{0}, operands, [&](std::size_t o) {
    const std::span<const std::array<IntPoint, 3>> own = corners.subspan(t.begin[o], t.begin[o + 1] - t.begin[o]);
    boxes[o].resize(own.size());
    for (std::size_t i = 0; i < own.size(); ++i) boxes[o][i] = box_of(own[i]);
    bounds[o] = TriangleTree::bounds(boxes[o]);
  });
  // Cells over the operands' common bounds, where they are as fine as over
  // each one's own: the trees' orders then merge into one tree over all
  // (TriangleTree::merged; combined_search.cpp) without a sort.
  Box32 all;
  for (const Box32& b : bounds) all.add(b);
  if (common_cells)
    for (std::size_t o = 0; o < operands; ++o) common_cells &= TriangleTree::same_cell_size(bounds[o], all);
  tbb::parallel_for(std::size_t{0}, operands, [&](std::size_t o) {
    t.tree[o] = TriangleTree(boxes[o], common_cells ? all : bounds[o]);
    boxes[o] = {};
  });
  if (diagonals) add_diagonals(t, corners);
  return t;
}

void add_diagonals(OperandTrees& t, std::span<const std::array<IntPoint, 3>> corners) {
  const std::size_t operands = t.begin.size() - 1;
  t.diagonals.resize(operands);
  tbb::parallel_for(std::size_t{0}, operands, [&](std::size_t o) {
    t.diagonals[o] = LeafDiagonals(t.tree[o], corners.subspan(t.begin[o], t.begin[o + 1] - t.begin[o]));
  });
}

}  // namespace ember::core
