// The root subproblem with a soup built on demand (root_problem.hpp).
#include "core/route/general/root_problem.hpp"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include "core/support/fill_vector.hpp"
#include "core/model/grid_triangles.hpp"
#include "core/route/general/subproblem.hpp"

namespace ember::core {

Soup root_soup(const GridTriangles& grid, std::span<const std::uint32_t> operand_begin) {
  const std::size_t n = grid.corners.size();
  Soup soup;
  reserve_touched(soup, n);
  soup.resize(n);
  // Unbuilt (soup.hpp): each points at its corners, which live in the grid
  // table for the whole Boolean. Each has area (build_grid_triangles).
  for (std::size_t o = 0; o + 1 < operand_begin.size(); ++o)
    tbb::parallel_for(tbb::blocked_range<std::uint32_t>(operand_begin[o], operand_begin[o + 1], 1024),
                      [&](const tbb::blocked_range<std::uint32_t>& r) {
                        for (std::uint32_t i = r.begin(); i != r.end(); ++i)
                          soup[i] = unbuilt_triangle(grid.corners[i], i, static_cast<std::uint32_t>(o));
                      });
  return soup;
}

const Subproblem& RootProblem::with_soup() {
  // Isolated: while the parallel build waits, this thread runs only its
  // own tasks. Otherwise it could pick up another task that asks for the
  // soup (two operands' proofs run side by side) and wait on itself.
  std::call_once(built_,
                 [&] { tbb::this_task_arena::isolate([&] { root_.soup = root_soup(*grid_, operand_begin_); }); });
  return root_;
}

}  // namespace ember::core
