// The broad phases' leaf extents (src/core/leaf_extents.hpp): per leaf slot,
// whether its triangle is apart from a given extent, through vector compares
// (4 lanes, and 8 where the processor has AVX2) and the portable loop alike,
// against extents_apart pair by pair; at the grid's limits, with touching
// extents, and with the empty slots of a partly filled last leaf. For both
// kinds: the four diagonals (LeafDiagonals, exact) and a frame's axes
// (LeafFrameExtents, widened past their rounding: checked against exact
// rational projections).
#include <gmpxx.h>
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "core/search/leaf_diagonals.hpp"
#include "core/search/leaf_frame_extents.hpp"

namespace ember::test {
namespace {

/// Random triangles with coordinates in [-range, range], as contact
/// triangles, and the tree over their boxes.
struct RandomTriangles {
  std::vector<std::array<IntPoint, 3>> corners;
  std::vector<core::ContactTriangle> tris;
  core::TriangleTree tree;

  RandomTriangles(std::size_t n, std::int64_t range, std::mt19937& rng) : corners(n), tris(n) {
    std::uniform_int_distribution<std::int64_t> at(-range, range);
    std::vector<core::Box32> boxes(n);
    for (std::size_t i = 0; i < n; ++i) {
      for (IntPoint& p : corners[i]) p = {at(rng), at(rng), at(rng)};
      tris[i].corners = &corners[i];
      boxes[i] = core::box_of(tris[i].p());
    }
    tree = core::TriangleTree(boxes);
  }
};

/// Checks every slot's stored extent against extent_of and every leaf's
/// masks against extents_apart pair by pair; counts apart / near pairs.
template <typename Leaves, typename ExtentOf>
void expect_masks_match(const core::TriangleTree& tree, const Leaves& leaves, std::size_t n, ExtentOf&& extent_of,
                        int& apart, int& near) {
  for (std::size_t s = 0; s < n; ++s) {
    const auto want = extent_of(tree.item(s));
    ASSERT_EQ(leaves.extent(s).lo, want.lo);
    ASSERT_EQ(leaves.extent(s).hi, want.hi);
  }
  for (std::size_t q = 0; q < n; ++q) {
    const auto e = extent_of(static_cast<std::uint32_t>(q));
    for (std::size_t leaf = tree.first_leaf(); leaf < tree.first_leaf() + (n + 7) / 8; ++leaf) {
      const auto [b, end] = tree.leaf_slots(leaf);
      unsigned want = 0;
      for (std::size_t s = b; s < end; ++s) {
        const bool d = core::extents_apart(e, extent_of(tree.item(s)));
        apart += d;
        near += !d;
        want |= static_cast<unsigned>(d) << (s - b);
      }
      const unsigned filled = end - b == 8 ? 0xffu : (1u << (end - b)) - 1;
      ASSERT_EQ(leaves.apart_mask(leaf, e) & filled, want) << "n " << n;
      ASSERT_EQ(leaves.apart_mask_portable(leaf, e) & filled, want) << "n " << n;
#if EMBER_WIDE_LANES
      if (core::cpu_has_avx2()) {  // the 8-lane test the broad phases take on this processor
        ASSERT_EQ(leaves.apart_mask_avx2(leaf, e) & filled, want) << "n " << n;
      }
#endif
    }
  }
}

TEST(LeafDiagonals, MasksMatchDiagonallyApartPairByPair) {
  std::mt19937 rng(29);
  int apart = 0, near = 0;
  for (const std::int64_t range : {std::int64_t{3}, std::int64_t{200}, kCoordLimit}) {
    for (const std::size_t n : {1u, 7u, 8u, 13u, 300u}) {
      // Small ranges: extents that touch (equal projections) abound.
      const RandomTriangles r(n, range, rng);
      const core::LeafDiagonals diagonals(r.tree, r.tris);
      const core::LeafDiagonals from_corners(r.tree, std::span<const std::array<IntPoint, 3>>(r.corners));
      const auto extent_of = [&](std::uint32_t i) { return core::diagonal_extent(r.corners[i]); };
      expect_masks_match(r.tree, diagonals, n, extent_of, apart, near);
      expect_masks_match(r.tree, from_corners, n, extent_of, apart,
                         near);  // the operand trees' (OperandTrees::diagonals)
    }
  }
  EXPECT_GT(apart, 10000);
  EXPECT_GT(near, 10000);
}

/// The slots of a leaf node that hold triangles (none for the leaves past
/// the last triangle).
std::size_t leaf_begin(const core::TriangleTree& tree, std::size_t leaf) {
  return std::min(tree.leaf_slots(leaf).first, tree.size());
}
std::size_t leaf_end(const core::TriangleTree& tree, std::size_t leaf) { return tree.leaf_slots(leaf).second; }

/// A random unit vector and a frame around it (not the coordinate axes).
core::FrameAxes random_frame(std::mt19937& rng) {
  std::normal_distribution<double> g;
  std::array<double, 3> e0{g(rng), g(rng), g(rng)};
  const double len = std::sqrt(e0[0] * e0[0] + e0[1] * e0[1] + e0[2] * e0[2]);
  for (double& x : e0) x /= len;
  core::FrameAxes frame;
  EXPECT_TRUE(core::frame_along(e0, frame));
  return frame;
}

TEST(LeafFrameExtents, MasksMatchExtentsApartPairByPair) {
  std::mt19937 rng(31);
  int apart = 0, near = 0;
  for (const std::int64_t range : {std::int64_t{3}, std::int64_t{200}, kCoordLimit}) {
    for (const std::size_t n : {1u, 7u, 8u, 13u, 300u}) {
      const RandomTriangles r(n, range, rng);
      const core::FrameAxes frame = random_frame(rng);
      const core::LeafFrameExtents leaves(r.tree, r.tris, frame);
      expect_masks_match(
          r.tree, leaves, n, [&](std::uint32_t i) { return core::frame_extent(r.corners[i], frame); }, apart, near);
    }
  }
  EXPECT_GT(apart, 10000);
  EXPECT_GT(near, 10000);
}

/// The leaf nodes under tree node `node` (heap order).
void leaves_under(const core::TriangleTree& tree, std::size_t node, std::vector<std::size_t>& out) {
  if (node >= tree.first_leaf()) {
    out.push_back(node);
    return;
  }
  leaves_under(tree, 2 * node + 1, out);
  leaves_under(tree, 2 * node + 2, out);
}

TEST(LeafFrameExtents, NodesApartExactlyWhereTheirTrianglesHullsAre) {
  // nodes_apart(a, b) prunes whole subtrees of the contact search: it must
  // hold only where every triangle under a is apart from every one under b,
  // and (to be worth it) wherever the hulls of their extents are apart.
  // Small triangles scattered over the range, so that many node pairs are
  // apart and many are not; the last leaves partly filled or empty.
  std::mt19937 rng(41);
  int apart = 0, near = 0;
  for (const std::int64_t range : {std::int64_t{40}, std::int64_t{5000}, kCoordLimit - 100}) {
    for (const std::size_t n : {1u, 9u, 70u, 300u}) {
      std::uniform_int_distribution<std::int64_t> at(-range, range), jitter(-range / 20, range / 20);
      std::vector<std::array<IntPoint, 3>> corners(n);
      std::vector<core::ContactTriangle> tris(n);
      std::vector<core::Box32> boxes(n);
      for (std::size_t i = 0; i < n; ++i) {
        const IntPoint c{at(rng), at(rng), at(rng)};
        for (IntPoint& p : corners[i]) p = {c.x + jitter(rng), c.y + jitter(rng), c.z + jitter(rng)};
        tris[i].corners = &corners[i];
        boxes[i] = core::box_of(tris[i].p());
      }
      const core::TriangleTree tree(boxes);
      const core::FrameAxes frame = random_frame(rng);
      const core::LeafFrameExtents leaves(tree, tris, frame);
      const std::size_t nodes = 2 * tree.first_leaf() + 1;
      for (std::size_t a = 0; a < nodes; ++a) {
        for (std::size_t b = 0; b < nodes; ++b) {
          std::vector<std::size_t> la, lb;
          leaves_under(tree, a, la);
          leaves_under(tree, b, lb);
          std::vector<core::ProjectedExtent<3>> ea, eb;
          for (const std::size_t leaf : la)
            for (std::size_t s = leaf_begin(tree, leaf); s < leaf_end(tree, leaf); ++s)
              ea.push_back(core::frame_extent(corners[tree.item(s)], frame));
          for (const std::size_t leaf : lb)
            for (std::size_t s = leaf_begin(tree, leaf); s < leaf_end(tree, leaf); ++s)
              eb.push_back(core::frame_extent(corners[tree.item(s)], frame));
          // The hulls apart along an axis; a node without triangles is
          // apart from everything.
          bool hulls_apart = ea.empty() || eb.empty();
          for (std::size_t k = 0; k < 3 && !hulls_apart; ++k) {
            std::int64_t alo = INT64_MAX, ahi = INT64_MIN, blo = INT64_MAX, bhi = INT64_MIN;
            for (const auto& e : ea) alo = std::min(alo, e.lo[k]), ahi = std::max(ahi, e.hi[k]);
            for (const auto& e : eb) blo = std::min(blo, e.lo[k]), bhi = std::max(bhi, e.hi[k]);
            hulls_apart = ahi < blo || bhi < alo;
          }
          ASSERT_EQ(leaves.nodes_apart(a, b), hulls_apart) << "n " << n << " nodes " << a << ", " << b;
          if (hulls_apart) {
            for (const auto& x : ea)
              for (const auto& y : eb) ASSERT_TRUE(core::extents_apart(x, y));
          }
          apart += hulls_apart && !ea.empty() && !eb.empty();
          near += !hulls_apart;
        }
      }
    }
  }
  EXPECT_GT(apart, 5000);
  EXPECT_GT(near, 5000);
}

TEST(LeafFrameExtents, BoundsHoldTheExactProjectionsAtTheGridsLimits) {
  // frame_extent's bounds must hold the exact projection of every corner
  // (rationals: the axes' doubles are exact binary fractions), fit int32,
  // and stay within a few units of the exact range (else the filter would
  // be sound but useless). Corners at and near the grid's limit +-2^25.
  std::mt19937 rng(37);
  const std::int64_t m = kCoordLimit;
  std::uniform_int_distribution<std::int64_t> any(-m, m), edge(m - 3, m), sign(0, 1);
  for (int round = 0; round < 3000; ++round) {
    const core::FrameAxes frame = random_frame(rng);
    std::array<IntPoint, 3> p;
    for (IntPoint& q : p) {
      if (round % 2 == 0) {
        q = {any(rng), any(rng), any(rng)};
      } else {  // a corner of the grid's cube, or next to it
        const auto c = [&] { return sign(rng) ? edge(rng) : -edge(rng); };
        q = {c(), c(), c()};
      }
    }
    const core::ProjectedExtent<3> e = core::frame_extent(p, frame);
    for (std::size_t a = 0; a < 3; ++a) {
      mpq_class lo, hi;
      for (std::size_t k = 0; k < 3; ++k) {
        const mpq_class s = mpq_class(frame[a][0]) * mpq_class(static_cast<double>(p[k].x)) +
                            mpq_class(frame[a][1]) * mpq_class(static_cast<double>(p[k].y)) +
                            mpq_class(frame[a][2]) * mpq_class(static_cast<double>(p[k].z));
        if (k == 0 || s < lo) lo = s;
        if (k == 0 || s > hi) hi = s;
      }
      ASSERT_LE(mpq_class(static_cast<double>(e.lo[a])), lo) << "round " << round << " axis " << a;
      ASSERT_GE(mpq_class(static_cast<double>(e.hi[a])), hi) << "round " << round << " axis " << a;
      ASSERT_LE(mpq_class(static_cast<double>(e.lo[a])), lo - 1) << "the widening is at least 1";
      ASSERT_GE(mpq_class(static_cast<double>(e.lo[a])), lo - 4) << "and at most a few units";
      ASSERT_LE(mpq_class(static_cast<double>(e.hi[a])), hi + 4);
      ASSERT_GE(e.lo[a], std::numeric_limits<std::int32_t>::min());
      ASSERT_LE(e.hi[a], std::numeric_limits<std::int32_t>::max());
    }
  }
}

}  // namespace
}  // namespace ember::test
