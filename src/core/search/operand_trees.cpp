// Per-operand triangle trees and leaf diagonals (operand_trees.hpp).
#include "core/search/operand_trees.hpp"

#include <tbb/parallel_for.h>

namespace ember::core {

OperandTrees build_operand_trees(std::vector<std::uint32_t> begin, std::span<const std::array<IntPoint, 3>> corners) {
  OperandTrees t;
  t.begin = std::move(begin);
  const std::size_t operands = t.begin.size() - 1;
  t.tree.resize(operands);
  t.diagonals.resize(operands);
  tbb::parallel_for(std::size_t{0}, operands, [&](std::size_t o) {
    const std::span<const std::array<IntPoint, 3>> own = corners.subspan(t.begin[o], t.begin[o + 1] - t.begin[o]);
    std::vector<Box32> boxes(own.size());
    for (std::size_t i = 0; i < boxes.size(); ++i) boxes[i] = box_of(own[i]);
    t.tree[o] = TriangleTree(boxes);
    t.diagonals[o] = LeafDiagonals(t.tree[o], own);
  });
  return t;
}

}  // namespace ember::core
