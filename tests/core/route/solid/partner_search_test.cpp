// The solid path's partner search (src/core/solid_path.hpp, find_partners):
// through the operands' trees, boxes, diagonal extents (operand_trees.hpp)
// and the box-beside-plane filter, it must report exactly the pairs of
// triangles of different operands that meet (triangles_meet, closed sets),
// each in both lists, sorted: compared here with every pair tested, on
// crowded small-range soups (touching, coplanar and vertex-sharing pairs
// abound), sparse ones at the grid's full range, and three operands.
#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <optional>
#include <random>
#include <span>
#include <vector>

#include "support/contact_fixtures.hpp"
#include "core/search/leaf_frame_extents.hpp"
#include "core/search/operand_trees.hpp"
#include "core/route/solid/solid_route.hpp"

namespace ember::test {
namespace {

/// `count` random non-degenerate triangles with corners in [-range, range]^3
/// and sides up to `size`.
std::vector<std::array<IntPoint, 3>> random_triangles(std::mt19937& rng, std::size_t count, std::int64_t range,
                                                      std::int64_t size) {
  std::uniform_int_distribution<std::int64_t> at(-range, range), step(-size, size);
  const auto clamp = [&](std::int64_t v) { return std::clamp(v, -range, range); };
  std::vector<std::array<IntPoint, 3>> out;
  while (out.size() < count) {
    const IntPoint p{at(rng), at(rng), at(rng)};
    std::array<IntPoint, 3> t{p, p, p};
    for (int k = 1; k < 3; ++k) t[k] = {clamp(p.x + step(rng)), clamp(p.y + step(rng)), clamp(p.z + step(rng))};
    if (grid_normal(t[0], t[1], t[2]) != std::array<std::int64_t, 3>{0, 0, 0}) out.push_back(t);
  }
  return out;
}

/// find_partners on operands of the given sizes (ids in operand order)
/// against every cross-operand pair tested exactly.
void expect_exact_partners(const std::vector<std::vector<std::array<IntPoint, 3>>>& operands, std::size_t& meeting) {
  core::GridTriangles grid;
  std::vector<std::uint32_t> begin{0}, operand_of;
  for (std::size_t o = 0; o < operands.size(); ++o) {
    for (const auto& t : operands[o]) {
      grid.corners.push_back(t);
      operand_of.push_back(static_cast<std::uint32_t>(o));
    }
    begin.push_back(static_cast<std::uint32_t>(grid.corners.size()));
  }
  set_normals(grid);
  const std::size_t n = grid.corners.size();
  const core::OperandTrees trees = core::build_operand_trees(begin, grid.corners);
  const std::atomic<bool> never{false};
  const core::Partners found = core::find_partners(grid, trees, n, never);
  ASSERT_EQ(found.begin.size(), n + 1);
  for (std::uint32_t x = 0; x < n; ++x) {
    std::vector<std::uint32_t> want;
    for (std::uint32_t y = 0; y < n; ++y)
      if (operand_of[x] != operand_of[y] && core::triangles_meet(grid.corners[x], grid.corners[y])) want.push_back(y);
    const std::span<const std::uint32_t> got = found.of(x);
    ASSERT_EQ(std::vector<std::uint32_t>(got.begin(), got.end()), want) << "triangle " << x;
    meeting += want.size();
  }
}

TEST(PartnerSearch, FindsExactlyTheMeetingPairsOfCrowdedSoups) {
  std::mt19937 rng(71);
  std::size_t meeting = 0;
  for (const std::int64_t range : {std::int64_t{4}, std::int64_t{40}, std::int64_t{1000}})
    for (const std::size_t n : {std::size_t{1}, std::size_t{9}, std::size_t{200}})
      expect_exact_partners(
          {random_triangles(rng, n, range, range / 2 + 1), random_triangles(rng, 150, range, range / 3 + 1)}, meeting);
  EXPECT_GT(meeting, 1000u) << meeting;  // the soups do meet, touching included
}

TEST(PartnerSearch, FindsExactlyTheMeetingPairsAtTheGridsFullRange) {
  std::mt19937 rng(72);
  std::size_t meeting = 0;
  // Long triangles across the whole grid, and small ones among them.
  for (int round = 0; round < 3; ++round)
    expect_exact_partners({random_triangles(rng, 300, kCoordLimit, kCoordLimit),
                           random_triangles(rng, 300, kCoordLimit, kCoordLimit / 16)},
                          meeting);
  EXPECT_GT(meeting, 50u) << meeting;
}

TEST(PartnerSearch, ThreeOperandsPairEveryTwo) {
  std::mt19937 rng(73);
  std::size_t meeting = 0;
  expect_exact_partners(
      {random_triangles(rng, 100, 20, 10), random_triangles(rng, 60, 20, 10), random_triangles(rng, 80, 20, 10)},
      meeting);
  EXPECT_GT(meeting, 200u) << meeting;
}

TEST(PartnerSearch, ACommonFrameDismissesTwoRodsPairsButNoPairThatMeets) {
  // Two rods of slivers off the axes, one through the other (as EMBER case
  // 582's and 16's sliver operands lie in their partners): the search takes
  // a common frame (partner_frame) whose extents and node hulls dismiss most
  // box pairs, and must still report exactly the pairs that meet. At the
  // origin and next to the grid's limit. Ordinary soups get no frame.
  const std::int64_t far = kCoordLimit - 40000;
  std::size_t meeting = 0;
  for (const IntPoint& centre : {IntPoint{0, 0, 0}, IntPoint{far, -far, far}}) {
    const std::vector<Tri> a = sliver_rod(500, centre, 43);
    const std::vector<Tri> b = sliver_rod(300, {centre.x + 900, centre.y + 400, centre.z - 300}, 44);
    std::vector<core::Box32> b_boxes;
    for (const Tri& t : b) b_boxes.push_back(core::box_of(t));
    const core::TriangleTree b_tree(b_boxes);
    const std::optional<core::FrameAxes> frame = core::partner_frame(a, b, b_tree);
    ASSERT_TRUE(frame.has_value());
    // The frame is worth it: most box pairs lie apart in it.
    std::size_t box_pairs = 0, apart = 0;
    for (const Tri& s : a)
      for (const Tri& t : b) {
        if (!core::overlap(core::box_of(s), core::box_of(t))) continue;
        ++box_pairs;
        apart += core::extents_apart(core::frame_extent(s, *frame), core::frame_extent(t, *frame));
      }
    EXPECT_GT(apart, box_pairs / 2) << apart << " of " << box_pairs;
    expect_exact_partners({a, b}, meeting);
  }
  EXPECT_GT(meeting, 100u) << meeting;
  std::mt19937 rng(75);
  const auto x = random_triangles(rng, 300, 1000, 300), y = random_triangles(rng, 300, 1000, 300);
  std::vector<core::Box32> y_boxes;
  for (const auto& t : y) y_boxes.push_back(core::box_of(t));
  EXPECT_FALSE(core::partner_frame(x, y, core::TriangleTree(y_boxes)).has_value());
}

/// A partner search started before the proof ended is bounded
/// (kSpeculativePartnersPerTriangle): past its budget it gives up and
/// reports no pairs; within it the answer is the exact one.
TEST(PartnerSearch, GivesUpPastItsBudgetAndOnlyThen) {
  std::mt19937 rng(74);
  // Crowded: nearly every box meets nearly every other (~200 x 150 box pairs).
  const auto a = random_triangles(rng, 200, 4, 3), b = random_triangles(rng, 150, 4, 2);
  core::GridTriangles grid;
  grid.corners.assign(a.begin(), a.end());
  grid.corners.insert(grid.corners.end(), b.begin(), b.end());
  set_normals(grid);
  const std::size_t n = grid.corners.size();
  const core::OperandTrees trees = core::build_operand_trees({0, 200, static_cast<std::uint32_t>(n)}, grid.corners);
  const std::atomic<bool> never{false};
  const core::Partners all = core::find_partners(grid, trees, n, never);
  ASSERT_FALSE(all.gave_up);
  ASSERT_GT(all.ids.size(), 1000u);
  const core::Partners bounded = core::find_partners(grid, trees, n, never, 1000);
  EXPECT_TRUE(bounded.gave_up);
  EXPECT_TRUE(bounded.ids.empty());
  const core::Partners roomy = core::find_partners(grid, trees, n, never, 1000 * n);
  EXPECT_FALSE(roomy.gave_up);
  EXPECT_EQ(roomy.begin, all.begin);
  EXPECT_EQ(roomy.ids, all.ids);
}

}  // namespace
}  // namespace ember::test
