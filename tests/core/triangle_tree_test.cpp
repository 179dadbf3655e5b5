// The triangle tree (src/core/triangle_tree.hpp): every query finds exactly
// the boxes that meet it (closed boxes: touching counts), leaf by leaf
// through the vector overlap mask and its portable twin, including boxes and
// queries at the int32 limits and partly filled last leaves.
#include <gtest/gtest.h>

#include <algorithm>
#include <limits>
#include <random>
#include <vector>

#include "core/triangle_tree.hpp"

namespace ember::test {
namespace {

using core::Box32;
using core::TriangleTree;

Box32 random_box(std::mt19937& rng, std::int32_t range, std::int32_t extent) {
  std::uniform_int_distribution<std::int32_t> at(-range, range), size(0, extent);
  Box32 b;
  for (int a = 0; a < 3; ++a) {
    b.lo[a] = at(rng);
    b.hi[a] = b.lo[a] + size(rng);
  }
  return b;
}

/// The slots of the tree's leaves whose boxes meet q, by brute force.
std::vector<std::uint32_t> brute_force(const std::vector<Box32>& boxes, const Box32& q) {
  std::vector<std::uint32_t> out;
  for (std::uint32_t i = 0; i < boxes.size(); ++i)
    if (core::overlap(boxes[i], q)) out.push_back(i);
  return out;
}

void check_tree(const std::vector<Box32>& boxes, const std::vector<Box32>& queries) {
  const TriangleTree tree(boxes);
  ASSERT_EQ(tree.size(), boxes.size());
  for (std::size_t s = 0; s < tree.size(); ++s) {
    const Box32 b = tree.box(s), want = boxes[tree.item(s)];
    ASSERT_EQ(b.lo, want.lo);
    ASSERT_EQ(b.hi, want.hi);
  }
  for (const Box32& q : queries) {
    std::vector<std::uint32_t> found;
    tree.for_each_overlapping(q, [&](std::uint32_t item) { found.push_back(item); });
    std::sort(found.begin(), found.end());
    EXPECT_EQ(found, brute_force(boxes, q));
    for (std::size_t leaf = tree.first_leaf(); leaf < tree.first_leaf() + (tree.size() + 7) / 8; ++leaf) {
      const auto [b, e] = tree.leaf_slots(leaf);
      unsigned want = 0;
      for (std::size_t s = b; s < e; ++s) want |= static_cast<unsigned>(core::overlap(tree.box(s), q)) << (s - b);
      ASSERT_EQ(tree.overlap_mask(leaf, q), want);
      ASSERT_EQ(tree.overlap_mask_portable(leaf, q), want);
    }
  }
}

TEST(TriangleTree, QueriesFindExactlyTheMeetingBoxes) {
  static_assert(TriangleTree::kLeaf == 8, "the test walks leaves of 8");
  std::mt19937 rng(5);
  for (const std::size_t n : {1u, 7u, 8u, 9u, 100u, 1000u}) {
    // A small lattice: many boxes touch exactly.
    std::vector<Box32> boxes(n), queries(200);
    for (Box32& b : boxes) b = random_box(rng, 20, 4);
    for (Box32& q : queries) q = random_box(rng, 24, 6);
    check_tree(boxes, queries);
  }
}

TEST(TriangleTree, ExtremeCoordinatesAndClampedQueries) {
  // Boxes at the grid's limit, and queries clamped to the whole int32 range
  // (enclosing_box of a huge double box): the last leaf's empty slots must
  // not answer.
  constexpr std::int32_t lim = 1 << 25, imin = std::numeric_limits<std::int32_t>::min(),
                         imax = std::numeric_limits<std::int32_t>::max();
  std::mt19937 rng(9);
  std::vector<Box32> boxes(13);
  for (Box32& b : boxes) b = random_box(rng, lim - (1 << 20), 1 << 20);
  boxes[0] = {{-lim, -lim, -lim}, {-lim, -lim, -lim}};
  boxes[1] = {{lim, lim, lim}, {lim, lim, lim}};
  std::vector<Box32> queries = {{{imin, imin, imin}, {imax, imax, imax}},
                                {{imin, imin, imin}, {-lim, -lim, -lim}},
                                {{lim, lim, lim}, {imax, imax, imax}},
                                core::enclosing_box({-1e300, -1e300, -1e300}, {1e300, 1e300, 1e300})};
  for (int k = 0; k < 100; ++k) queries.push_back(random_box(rng, lim, 1 << 24));
  check_tree(boxes, queries);
  std::vector<std::uint32_t> all;
  TriangleTree(boxes).for_each_overlapping(queries[0], [&](std::uint32_t item) { all.push_back(item); });
  EXPECT_EQ(all.size(), boxes.size());
}

}  // namespace
}  // namespace ember::test
