// The root soup built on demand (root_problem.hpp): the same polygons the
// set-up used to build up front, once, whichever threads ask for it.
#include <gtest/gtest.h>

#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <atomic>
#include <random>
#include <vector>

#include "core/route/general/root_problem.hpp"
#include "core/model/grid_triangles.hpp"
#include "core/model/output_polygon.hpp"
#include "core/route/general/subproblem.hpp"

namespace ember::core {
namespace {

/// n random grid triangles (non-degenerate with overwhelming probability).
GridTriangles random_triangles(std::size_t n) {
  std::mt19937_64 rng(5);
  std::uniform_int_distribution<std::int64_t> coord(-(std::int64_t{1} << 25), std::int64_t{1} << 25);
  GridTriangles g;
  g.corners.resize(n);
  for (auto& t : g.corners)
    for (IntPoint& p : t) p = {coord(rng), coord(rng), coord(rng)};
  return g;
}

TEST(RootProblem, SoupIsEveryTriangleUnbuiltWithItsOperand) {
  const GridTriangles grid = random_triangles(5000);
  const std::vector<std::uint32_t> begin{0, 1200, 1200, 5000};  // the middle operand has none
  const Soup soup = root_soup(grid, begin);
  ASSERT_EQ(soup.size(), grid.corners.size());
  for (std::uint32_t i = 0; i < soup.size(); ++i) {
    const SoupPolygon want = unbuilt_triangle(grid.corners[i], i, i < 1200 ? 0 : 2);
    EXPECT_TRUE(unbuilt(soup[i]));
    EXPECT_EQ(soup[i].id, i);
    EXPECT_EQ(soup[i].operand, want.operand) << i;
    EXPECT_EQ(soup[i].corners, &grid.corners[i]);
    EXPECT_EQ(soup[i].lo, want.lo);
    EXPECT_EQ(soup[i].hi, want.hi);
  }
}

TEST(RootProblem, BuiltOnceWhicheverThreadsAsk) {
  const GridTriangles grid = random_triangles(70000);
  Subproblem shell;
  shell.ref_w.assign(2, 0);
  shell.box.lo = {-7, -8, -9};
  RootProblem root(std::move(shell), grid, {0, 30000, 70000});
  EXPECT_EQ(root.operands(), 2u);
  EXPECT_EQ(root.box().lo[2], -9);
  // Many tasks ask at once, from inside parallel work (the proofs of two
  // operands do): each sees the whole soup, never one still being built,
  // and no task waits on itself (the build is isolated: a hang here).
  std::atomic<int> mismatches{0};
  tbb::task_arena(4).execute([&] {
    tbb::parallel_for(0, 256, [&](int) {
      const Subproblem& full = root.with_soup();
      if (full.soup.size() != grid.corners.size() || full.soup.back().operand != 1 || !unbuilt(full.soup[12345]))
        ++mismatches;
    });
  });
  EXPECT_EQ(mismatches.load(), 0);
  const Subproblem taken = root.take();
  ASSERT_EQ(taken.soup.size(), grid.corners.size());
  EXPECT_EQ(taken.soup[29999].operand, 0u);
  EXPECT_EQ(taken.soup[30000].operand, 1u);
  EXPECT_EQ(taken.box.lo[1], -8);
}

}  // namespace
}  // namespace ember::core
