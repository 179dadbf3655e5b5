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
  if (diagonals) t.diagonals.resize(operands);
  const auto own = [&](std::size_t o) { return corners.subspan(t.begin[o], t.begin[o + 1] - t.begin[o]); };
  const auto boxes_of = [&](std::size_t o) {
    std::vector<Box32> boxes(own(o).size());
    for (std::size_t i = 0; i < boxes.size(); ++i) boxes[i] = box_of(own(o)[i]);
    return boxes;
  };
  if (!common_cells) {  // one task per operand (small inputs: a fork-join less per step)
    tbb::parallel_for(std::size_t{0}, operands, [&](std::size_t o) {
      t.tree[o] = TriangleTree(boxes_of(o));
      if (diagonals) t.diagonals[o] = LeafDiagonals(t.tree[o], own(o));
    });
    return t;
  }
  // Cells over the operands' common bounds, where they are as fine as over
  // each one's own: the trees' orders then merge into one tree over all
  // (TriangleTree::merged; combined_search.cpp) without a sort.
  std::vector<std::vector<Box32>> boxes(operands);
  std::vector<Box32> bounds(operands);
  tbb::parallel_for(std::size_t{0}, operands, [&](std::size_t o) {
    boxes[o] = boxes_of(o);
    bounds[o] = TriangleTree::bounds(boxes[o]);
  });
  Box32 all;
  for (const Box32& b : bounds) all.add(b);
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
