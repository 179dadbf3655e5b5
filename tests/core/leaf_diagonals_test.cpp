// The proof's diagonal masks (src/core/leaf_diagonals.hpp): per leaf slot,
// whether its triangle is diagonally apart from a given extent, through
// vector compares (4 lanes, and 8 where the processor has AVX2) and the
// portable loop alike, against diagonally_apart pair by pair; at the grid's
// limits, with touching extents, and with the empty slots of a partly filled
// last leaf.
#include <gtest/gtest.h>

#include <random>
#include <vector>

#include "core/leaf_diagonals.hpp"

namespace ember::test {
namespace {

TEST(LeafDiagonals, MasksMatchDiagonallyApartPairByPair) {
  std::mt19937 rng(29);
  int apart = 0, near = 0;
  for (const std::int64_t range : {std::int64_t{3}, std::int64_t{200}, kCoordLimit}) {
    for (const std::size_t n : {1u, 7u, 8u, 13u, 300u}) {
      // Small ranges: extents that touch (equal projections) abound.
      std::uniform_int_distribution<std::int64_t> at(-range, range);
      std::vector<core::ContactTriangle> tris(n);
      std::vector<std::array<IntPoint, 3>> corners(n);
      std::vector<core::Box32> boxes(n);
      for (std::size_t i = 0; i < n; ++i) {
        for (IntPoint& p : corners[i]) p = {at(rng), at(rng), at(rng)};
        tris[i].corners = &corners[i];
        boxes[i] = core::box_of(tris[i].p());
      }
      const core::TriangleTree tree(boxes);
      const core::LeafDiagonals diagonals(tree, tris);
      const core::LeafDiagonals from_corners(tree, std::span<const std::array<IntPoint, 3>>(corners));
      for (std::size_t s = 0; s < n; ++s) {
        const core::DiagonalExtent want = core::diagonal_extent(tris[tree.item(s)].p());
        ASSERT_EQ(diagonals.extent(s).lo, want.lo);
        ASSERT_EQ(diagonals.extent(s).hi, want.hi);
        ASSERT_EQ(from_corners.extent(s).lo, want.lo);  // the operand trees' (OperandTrees::diagonals)
        ASSERT_EQ(from_corners.extent(s).hi, want.hi);
      }
      for (std::size_t q = 0; q < n; ++q) {
        const core::DiagonalExtent e = core::diagonal_extent(tris[q].p());
        for (std::size_t leaf = tree.first_leaf(); leaf < tree.first_leaf() + (n + 7) / 8; ++leaf) {
          const auto [b, end] = tree.leaf_slots(leaf);
          unsigned want = 0;
          for (std::size_t s = b; s < end; ++s) {
            const bool d = core::diagonally_apart(e, core::diagonal_extent(tris[tree.item(s)].p()));
            apart += d;
            near += !d;
            want |= static_cast<unsigned>(d) << (s - b);
          }
          const unsigned filled = end - b == 8 ? 0xffu : (1u << (end - b)) - 1;
          ASSERT_EQ(diagonals.apart_mask(leaf, e) & filled, want) << "range " << range << " n " << n;
          ASSERT_EQ(diagonals.apart_mask_portable(leaf, e) & filled, want) << "range " << range << " n " << n;
#if EMBER_WIDE_LANES
          if (core::cpu_has_avx2()) {  // the 8-lane test the broad phases take on this processor
            ASSERT_EQ(diagonals.apart_mask_avx2(leaf, e) & filled, want) << "range " << range << " n " << n;
          }
#endif
        }
      }
    }
  }
  EXPECT_GT(apart, 10000);
  EXPECT_GT(near, 10000);
}

}  // namespace
}  // namespace ember::test
