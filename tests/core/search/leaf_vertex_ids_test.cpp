// The proof's neighbour masks (src/core/leaf_vertex_ids.hpp): per leaf
// slot, whether its triangle shares one or two vertex ids with a given
// triangle, and whether it shares any, through vector compares (4 lanes, and
// 8 where the processor has AVX2) and the portable loop alike, against a
// brute-force count; empty slots of a partly filled last leaf never answer.
#include <gtest/gtest.h>

#include <random>
#include <vector>

#include "core/search/leaf_vertex_ids.hpp"

namespace ember::test {
namespace {

TEST(LeafVertexIds, MasksMatchSharedVertexCounts) {
  std::mt19937 rng(23);
  int one = 0, two = 0, three = 0;
  for (const std::size_t n : {1u, 7u, 8u, 13u, 200u}) {
    // Few distinct ids: one, two and three shared vertices all occur.
    std::uniform_int_distribution<std::uint32_t> id(0, 9);
    std::uniform_int_distribution<std::int64_t> at(-100, 100);
    std::vector<core::ContactTriangle> tris(n);
    std::vector<std::array<IntPoint, 3>> corners(n);
    std::vector<core::Box32> boxes(n);
    for (std::size_t i = 0; i < n; ++i) {
      const std::uint32_t a = id(rng);
      std::uint32_t b = id(rng), c = id(rng);
      while (b == a) b = id(rng);
      while (c == a || c == b) c = id(rng);
      tris[i].id = {a, b, c};
      for (IntPoint& p : corners[i]) p = {at(rng), at(rng), at(rng)};
      tris[i].corners = &corners[i];
      boxes[i] = core::box_of(tris[i].p());
    }
    const core::TriangleTree tree(boxes);
    const core::LeafVertexIds ids(tree, tris);
    for (int q = 0; q < 200; ++q) {
      const std::array<std::uint32_t, 3> query = tris[rng() % n].id;
      for (std::size_t leaf = tree.first_leaf(); leaf < tree.first_leaf() + (n + 7) / 8; ++leaf) {
        const auto [b, e] = tree.leaf_slots(leaf);
        core::LeafVertexIds::Masks want;
        for (std::size_t s = b; s < e; ++s) {
          int shared = 0;
          for (const std::uint32_t u : tris[tree.item(s)].id)
            for (const std::uint32_t v : query) shared += u == v;
          one += shared == 1;
          two += shared == 2;
          three += shared == 3;
          want.neighbours |= static_cast<unsigned>(shared == 1 || shared == 2) << (s - b);
          want.sharing |= static_cast<unsigned>(shared > 0) << (s - b);
        }
        ASSERT_TRUE(ids.shared_masks(leaf, query) == want);
        ASSERT_TRUE(ids.shared_masks_portable(leaf, query) == want);
#if EMBER_WIDE_LANES
        if (core::cpu_has_avx2()) {
          ASSERT_TRUE(ids.shared_masks_avx2(leaf, query) == want);  // what the search takes here
        }
#endif
      }
    }
  }
  EXPECT_GT(one, 1000);
  EXPECT_GT(two, 1000);
  EXPECT_GT(three, 100);
}

}  // namespace
}  // namespace ember::test
