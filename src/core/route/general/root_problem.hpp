#pragma once
// The Boolean's root subproblem, whose soup is built only where it is read.
//
// The root soup (soup.hpp: 80 bytes per input triangle, each entry's double
// box worked out from its corners) is what the subdivision of the general
// path starts from. The solid path and the proof with operand trees never
// read it: they work on the grid triangles (GridTriangles::corners) and the
// operands' id ranges. Building it up front would cost a pass over every
// input triangle and 80 bytes per input triangle at the solid path's peak,
// for inputs that then never use it.
#include <cstdint>
#include <mutex>
#include <span>
#include <vector>

#include "core/route/general/subproblem.hpp"

namespace ember::core {

struct GridTriangles;

/// The soup of every grid triangle, unbuilt: polygon i is triangle i, of the
/// operand whose id range holds it (operand_begin[o] .. operand_begin[o + 1]).
/// `grid` must outlive the soup (its entries point at grid.corners).
Soup root_soup(const GridTriangles& grid, std::span<const std::uint32_t> operand_begin);

class RootProblem {
 public:
  /// `shell`: the root's box, reference point and winding numbers (its soup
  /// empty); `grid` and `operand_begin` as for root_soup. `grid` must
  /// outlive this object and every soup it hands out.
  RootProblem(Subproblem shell, const GridTriangles& grid, std::vector<std::uint32_t> operand_begin)
      : root_(std::move(shell)), grid_(&grid), operand_begin_(std::move(operand_begin)) {}

  const Box& box() const { return root_.box; }
  std::size_t operands() const { return root_.ref_w.size(); }
  /// Operand o's triangles are ids [operand_begin()[o], operand_begin()[o + 1]).
  const std::vector<std::uint32_t>& operand_begin() const { return operand_begin_; }
  /// The root with its soup, built at the first call (once, whichever
  /// thread asks first; the others wait for it).
  const Subproblem& with_soup();
  /// The root with its soup, handed over (to the general path's solve).
  Subproblem take() {
    with_soup();
    return std::move(root_);
  }

 private:
  Subproblem root_;
  const GridTriangles* grid_;
  std::vector<std::uint32_t> operand_begin_;
  std::once_flag built_;
};

}  // namespace ember::core
