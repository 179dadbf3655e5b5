// The triangle tree (src/core/triangle_tree.hpp): every query finds exactly
// the boxes that meet it (closed boxes: touching counts), leaf by leaf
// through the vector overlap masks (4 lanes, and 8 where the processor has
// AVX2) and their portable twin, including boxes and queries at the int32
// limits and partly filled last leaves; the box-beside-plane filter
// against GMP; and the tree's order, a Hilbert curve, against Skilling's
// transform and by its defining property.
#include <gmpxx.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cstdlib>
#include <limits>
#include <set>
#include <random>
#include <vector>

#include "core/search/triangle_tree.hpp"

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
#if EMBER_WIDE_LANES
      if (core::cpu_has_avx2()) {
        ASSERT_EQ(tree.overlap_mask_avx2(leaf, q), want);  // what the broad phases take here
      }
#endif
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
  // Boxes at the grid's limit, and the widest queries the tree takes
  // (query_in_range: not the whole int32 range along x; enclosing_box of a
  // huge double box clamps to kQueryLimit): the last leaf's empty slots must
  // not answer.
  constexpr std::int32_t lim = 1 << 25, imin = std::numeric_limits<std::int32_t>::min(),
                         imax = std::numeric_limits<std::int32_t>::max(), q = core::kQueryLimit;
  std::mt19937 rng(9);
  std::vector<Box32> boxes(13);
  for (Box32& b : boxes) b = random_box(rng, lim - (1 << 20), 1 << 20);
  boxes[0] = {{-lim, -lim, -lim}, {-lim, -lim, -lim}};
  boxes[1] = {{lim, lim, lim}, {lim, lim, lim}};
  const Box32 clamped = core::enclosing_box({-1e300, -1e300, -1e300}, {1e300, 1e300, 1e300});
  EXPECT_EQ(clamped.lo, (std::array<std::int32_t, 3>{-q, -q, -q}));
  EXPECT_EQ(clamped.hi, (std::array<std::int32_t, 3>{q, q, q}));
  std::vector<Box32> queries = {{{-q, imin, imin}, {q, imax, imax}},
                                {{imin, imin, imin}, {-lim, -lim, -lim}},
                                {{lim, lim, lim}, {imax, imax, imax}},
                                {{imin + 1, imin, imin}, {imax, imax, imax}},
                                clamped};
  for (const Box32& b : queries) ASSERT_TRUE(core::query_in_range(b));
  for (int k = 0; k < 100; ++k) queries.push_back(random_box(rng, lim, 1 << 24));
  check_tree(boxes, queries);
  std::vector<std::uint32_t> all;
  TriangleTree(boxes).for_each_overlapping(queries[0], [&](std::uint32_t item) { all.push_back(item); });
  EXPECT_EQ(all.size(), boxes.size());
}

/// The exact sides (GMP) of the box's eight corners against the plane
/// through o with normal n: +1 or -1 if all are strictly on that side, else 0.
int gmp_box_side(const Box32& box, const IntPoint& o, const std::array<std::int64_t, 3>& n) {
  const auto z = [](std::int64_t v) { return mpz_class(static_cast<long>(v)); };
  int side = 0;
  for (int c = 0; c < 8; ++c) {
    mpz_class d = 0;
    const std::int64_t origin[3] = {o.x, o.y, o.z};
    for (int k = 0; k < 3; ++k)
      d += z(n[static_cast<std::size_t>(k)]) * (z(c >> k & 1 ? box.hi[k] : box.lo[k]) - z(origin[k]));
    const int s = sgn(d);
    if (s == 0 || (side != 0 && s != side)) return 0;
    side = s;
  }
  return side;
}

TEST(TriangleTree, BoxOfIsTheCornersMinimumAndMaximumPerAxis) {
  std::mt19937_64 rng(17);
  constexpr std::int64_t kMax = std::int64_t{1} << 25;  // the grid's range (kCoordLimit)
  std::uniform_int_distribution<std::int64_t> coord(-kMax, kMax);
  for (int trial = 0; trial < 2000; ++trial) {
    std::array<IntPoint, 3> t;
    for (IntPoint& p : t) {
      p = {coord(rng), coord(rng), coord(rng)};
      // The range's ends and repeated values too.
      if (trial % 7 == 0) p.x = trial % 2 ? kMax : -kMax;
      if (trial % 5 == 0) p.y = t[0].y;
    }
    const core::Box32 b = core::box_of(t);
    const auto check = [&](std::int64_t IntPoint::*c, int a) {
      const std::int64_t lo = std::min({t[0].*c, t[1].*c, t[2].*c}), hi = std::max({t[0].*c, t[1].*c, t[2].*c});
      EXPECT_EQ(b.lo[a], lo) << trial;
      EXPECT_EQ(b.hi[a], hi) << trial;
    };
    check(&IntPoint::x, 0);
    check(&IntPoint::y, 1);
    check(&IntPoint::z, 2);
  }
}

/// The place of (x, y, z) along a Hilbert curve through 2^(3 bits) cells by
/// J. Skilling's transform ("Programming the Hilbert curve", AIP Conf. Proc.
/// 707, 2004): the coordinates transposed in place, then interleaved with x
/// most significant at each level. Written from the paper, independently of
/// the tree's table.
std::uint32_t skilling_key(std::uint32_t x, std::uint32_t y, std::uint32_t z, int bits) {
  std::array<std::uint32_t, 3> v{x, y, z};
  const std::uint32_t top = 1u << (bits - 1);
  for (std::uint32_t q = top; q > 1; q >>= 1) {  // undo excess work
    const std::uint32_t p = q - 1;
    for (int i = 0; i < 3; ++i) {
      if (v[i] & q) {
        v[0] ^= p;  // invert
      } else {
        const std::uint32_t t = (v[0] ^ v[i]) & p;  // exchange
        v[0] ^= t;
        v[i] ^= t;
      }
    }
  }
  for (int i = 1; i < 3; ++i) v[i] ^= v[i - 1];  // Gray encode
  std::uint32_t t = 0;
  for (std::uint32_t q = top; q > 1; q >>= 1)
    if (v[2] & q) t ^= q - 1;
  for (int i = 0; i < 3; ++i) v[i] ^= t;
  std::uint32_t key = 0;
  for (int b = bits - 1; b >= 0; --b)
    for (int i = 0; i < 3; ++i) key = key << 1 | ((v[static_cast<std::size_t>(i)] >> b) & 1u);
  return key;
}

TEST(TreeOrder, HilbertKeyIsSkillingsCurve) {
  std::mt19937 rng(17);
  std::uniform_int_distribution<std::uint32_t> cell(0, 1023);
  for (int i = 0; i < 200000; ++i) {
    const std::uint32_t x = cell(rng), y = cell(rng), z = cell(rng);
    ASSERT_EQ(core::hilbert_key(x, y, z), skilling_key(x, y, z, 10)) << x << " " << y << " " << z;
  }
  for (std::uint32_t x : {0u, 1u, 511u, 512u, 1022u, 1023u})
    for (std::uint32_t y : {0u, 1u, 511u, 512u, 1023u})
      for (std::uint32_t z : {0u, 511u, 512u, 1023u}) EXPECT_EQ(core::hilbert_key(x, y, z), skilling_key(x, y, z, 10));
}

TEST(TreeOrder, HilbertKeyStepsBetweenFaceNeighbours) {
  // The curve enters at the origin, so the corner cube of 16^3 cells is its
  // first 4096 places: each taken once, and each cell along it a face
  // neighbour of the one before (what makes runs of the order compact).
  std::vector<std::array<std::uint32_t, 3>> along(4096, {~0u, ~0u, ~0u});
  for (std::uint32_t x = 0; x < 16; ++x)
    for (std::uint32_t y = 0; y < 16; ++y)
      for (std::uint32_t z = 0; z < 16; ++z) {
        const std::uint32_t key = core::hilbert_key(x, y, z);
        ASSERT_LT(key, 4096u);
        ASSERT_EQ(along[key][0], ~0u) << "place " << key << " taken twice";
        along[key] = {x, y, z};
      }
  for (std::size_t k = 1; k < along.size(); ++k) {
    int distance = 0;
    for (int a = 0; a < 3; ++a) distance += std::abs(static_cast<int>(along[k][a]) - static_cast<int>(along[k - 1][a]));
    EXPECT_EQ(distance, 1) << "places " << k - 1 << " and " << k;
  }
  // Across the whole grid: the curve runs from one corner cell (place 0) to
  // another (the last place).
  std::set<std::uint32_t> seen;
  for (std::uint32_t c : {0u, 1023u})
    for (std::uint32_t d : {0u, 1023u})
      for (std::uint32_t e : {0u, 1023u}) seen.insert(core::hilbert_key(c, d, e));
  EXPECT_EQ(seen.size(), 8u);
  EXPECT_TRUE(seen.count(0u) == 1 && seen.count((1u << 30) - 1) == 1) << "the curve runs from corner to corner";
}

TEST(BoxBesidePlane, NeverClaimsABoxThatTouchesThePlaneAndFindsClearOnes) {
  // Planes of random grid triangles over the whole grid (normal components
  // near 2^53) and boxes of every size: the filter must never call a box
  // beside that GMP finds touching or crossing the plane, and must find
  // nearly all boxes that are beside by a clear margin.
  constexpr std::int64_t lim = kCoordLimit;
  std::mt19937 rng(31);
  std::uniform_int_distribution<std::int64_t> at(-lim, lim);
  const auto point = [&] { return IntPoint{at(rng), at(rng), at(rng)}; };
  int beside = 0, found = 0;
  for (int n = 0; n < 40000; ++n) {
    const IntPoint a = point(), b = point(), c = point();
    const std::array<std::int64_t, 3> normal = grid_normal(a, b, c);
    if (normal == std::array<std::int64_t, 3>{}) continue;
    const int span = 1 << std::uniform_int_distribution<int>(0, 25)(rng);
    std::uniform_int_distribution<std::int64_t> size(0, span);
    Box32 box;
    for (int k = 0; k < 3; ++k) {
      const std::int64_t lo = std::max(-lim, at(rng) - span / 2);
      box.lo[k] = static_cast<std::int32_t>(lo);
      box.hi[k] = static_cast<std::int32_t>(std::min(lim, lo + size(rng)));
    }
    const int want = gmp_box_side(box, a, normal);
    const bool got = core::box_clearly_beside(box, a, normal);
    if (got) {
      ASSERT_NE(want, 0) << "n " << n;
    }
    beside += want != 0;
    found += got;
  }
  EXPECT_GT(beside, 10000);
  EXPECT_GT(found, beside - beside / 100);  // a filter that misses at most 1%
}

TEST(BoxBesidePlane, BoxesWithACornerOnThePlaneAreNeverBeside) {
  // The corner of the box farthest along the normal lies exactly on the plane
  // and every other corner below it: the exact answer is "touching", while
  // the double sums land on either side of zero at full-range coordinates
  // (without the filter's margin the test fails). Corners one unit further
  // down are beside, and the filter must see most of them.
  std::mt19937 rng(32);
  std::uniform_int_distribution<std::int64_t> at(-(1 << 23), 1 << 23), d(-(1 << 22), 1 << 22);
  std::uniform_int_distribution<std::int32_t> reach(0, 1 << 22);
  int tested = 0, shifted_found = 0, shifted_beside = 0;
  for (int n = 0; n < 40000; ++n) {
    const IntPoint a0{at(rng), at(rng), at(rng)}, d1{d(rng), d(rng), d(rng)}, d2{d(rng), d(rng), d(rng)};
    const IntPoint a1{a0.x + d1.x, a0.y + d1.y, a0.z + d1.z}, a2{a0.x + d2.x, a0.y + d2.y, a0.z + d2.z};
    const std::array<std::int64_t, 3> normal = grid_normal(a0, a1, a2);
    if (normal == std::array<std::int64_t, 3>{}) continue;
    const IntPoint on{a0.x + d1.x + d2.x, a0.y + d1.y + d2.y, a0.z + d1.z + d2.z};  // on the plane
    const std::int64_t p[3] = {on.x, on.y, on.z};
    Box32 box;
    for (int k = 0; k < 3; ++k) {
      const std::int32_t r = normal[static_cast<std::size_t>(k)] == 0 ? 0 : reach(rng);
      const bool up = normal[static_cast<std::size_t>(k)] > 0;  // the corner at p is the box's highest
      box.lo[k] = static_cast<std::int32_t>(up ? p[k] - r : p[k]);
      box.hi[k] = static_cast<std::int32_t>(up ? p[k] : p[k] + r);
    }
    ASSERT_EQ(gmp_box_side(box, a0, normal), 0);
    ++tested;
    ASSERT_FALSE(core::box_clearly_beside(box, a0, normal)) << "n " << n;
    // The same box moved one grid step down along the normal's dominant axis.
    int k = 0;
    for (int j = 1; j < 3; ++j)
      if (std::abs(normal[static_cast<std::size_t>(j)]) > std::abs(normal[static_cast<std::size_t>(k)])) k = j;
    const std::int32_t step = normal[static_cast<std::size_t>(k)] > 0 ? -1 : 1;
    box.lo[k] += step;
    box.hi[k] += step;
    const int want = gmp_box_side(box, a0, normal);
    const bool got = core::box_clearly_beside(box, a0, normal);
    if (got) {
      ASSERT_NE(want, 0);
    }
    shifted_beside += want != 0;
    shifted_found += got;
  }
  EXPECT_GT(tested, 30000);
  EXPECT_GT(shifted_beside, tested / 2);
  EXPECT_GT(shifted_found, 0);
}

}  // namespace
}  // namespace ember::test
