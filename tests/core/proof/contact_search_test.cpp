// The solid proof's broad phase (src/core/contact_search.hpp): the count of
// improper pairs it finds must equal an all-pairs count with the same exact
// predicate, whatever the sizes, positions and thread count; it stops at
// max_pairs and gives up on piles past its budget.
#include <gtest/gtest.h>

#include <tbb/task_arena.h>

#include <algorithm>
#include <atomic>
#include <optional>
#include <random>

#include "core/proof/contact_search.hpp"
#include "core/search/leaf_frame_extents.hpp"
#include "core/search/contact_triangle.hpp"
#include "core/search/extents.hpp"
#include "core/search/triangle_contact.hpp"
#include "core/search/triangle_tree.hpp"
#include "support/contact_fixtures.hpp"
#include "support/boolean_checks.hpp"

namespace ember::test {
namespace {

using core::ContactTriangle;

/// Small triangles scattered over a cube of side `extent` (many touch and
/// cross), with a few long ones across the whole cube, which inflate the
/// boxes of their leaves and of every node above them.
std::vector<Tri> scattered(std::size_t count, std::int64_t extent, std::int64_t size, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_int_distribution<std::int64_t> at(-extent, extent), d(-size, size);
  std::vector<Tri> tris;
  while (tris.size() < count) {
    const IntPoint c{at(rng), at(rng), at(rng)};
    Tri t{c, {c.x + d(rng), c.y + d(rng), c.z + d(rng)}, {c.x + d(rng), c.y + d(rng), c.z + d(rng)}};
    if (tris.size() % 97 == 5) t[1] = {-c.x, -c.y, c.z};                         // a long one
    if (tris.size() % 5 == 1 && !tris.empty()) t[0] = tris[tris.size() - 1][1];  // a shared vertex
    if (!degenerate(t)) tris.push_back(t);
  }
  return tris;
}

TEST(ContactSearch, CountEqualsAllPairsOnRandomSoups) {
  // Sizes around multiples of the leaf size and of powers of two, so that
  // leaves are partly filled and the tree has empty slots.
  for (const std::size_t n : {1u, 2u, 7u, 8u, 9u, 63u, 300u, 1500u}) {
    const std::vector<Tri> corners = scattered(n, 1000, 60, static_cast<unsigned>(n));
    const std::vector<ContactTriangle> tris = with_ids(corners);
    const std::size_t expected = all_pairs_count(tris);
    for (const int threads : {1, 2, 4}) {
      tbb::task_arena arena(threads);
      core::ContactSearchResult r;
      arena.execute([&] { r = core::find_contacts(tris, 1u << 30); });
      EXPECT_EQ(r.pairs, expected) << n << " triangles, " << threads << " threads";
      EXPECT_FALSE(r.gave_up);
    }
    if (n >= 300) {
      EXPECT_GT(expected, 10u) << "the soup should cross itself";
    }
  }
}

TEST(ContactSearch, DiagonalExtentsOnlyDismissDisjointTriangles) {
  // The diagonal filter (diagonally_apart) must never dismiss a pair that
  // meets or touches: over random soups, extreme coordinates and slivers
  // along a diagonal, every dismissed pair is one the exact test calls
  // apart and shares no vertex; and it does dismiss slivers that the boxes
  // cannot tell apart (a stack of triangles in the parallel planes
  // x + y + z = 10 k, whose boxes all overlap).
  std::vector<Tri> tris = scattered(600, 400, 80, 11);
  const std::int64_t m = kCoordLimit;
  tris.push_back({{{-m, -m, -m}, {m, m, m}, {m, m, m - 1}}});
  tris.push_back({{{-m, -m, -m + 1}, {m, m, m}, {m - 1, m, m}}});
  for (std::int64_t c = 0; c < 400; c += 10) tris.push_back({{{0, 0, c}, {1000, -1000, c}, {0, 500, c - 500}}});
  const std::vector<ContactTriangle> ct = with_ids(tris);
  std::size_t dismissed = 0;
  for (std::size_t i = 0; i < ct.size(); ++i)
    for (std::size_t j = i + 1; j < ct.size(); ++j) {
      if (!core::diagonally_apart(core::diagonal_extent(ct[i].p()), core::diagonal_extent(ct[j].p()))) continue;
      ++dismissed;
      EXPECT_FALSE(core::triangles_meet_improperly(ct[i], ct[j])) << i << ", " << j;
      for (const std::uint32_t a : ct[i].id)
        for (const std::uint32_t b : ct[j].id) EXPECT_NE(a, b) << i << ", " << j << " share a vertex";
    }
  EXPECT_GT(dismissed, 0u);
  std::size_t sliver_pairs = 0;  // the 40 slivers: boxes overlap pairwise, diagonals apart
  for (std::size_t i = ct.size() - 40; i < ct.size(); ++i)
    for (std::size_t j = i + 1; j < ct.size(); ++j)
      sliver_pairs += core::diagonally_apart(core::diagonal_extent(ct[i].p()), core::diagonal_extent(ct[j].p()));
  EXPECT_EQ(sliver_pairs, 40u * 39u / 2u);
  EXPECT_EQ(core::find_contacts(ct, 1u << 30).pairs, all_pairs_count(ct));
}

TEST(ContactSearch, ExtremeCoordinatesAreNotMissed) {
  // Boxes at the grid's limits (|x| <= 2^25): the Morton key and the int32
  // boxes must hold them.
  const std::int64_t m = kCoordLimit;
  const std::vector<Tri> tris{
      {{{-m, -m, -m}, {m, -m, -m}, {-m, m, m}}},
      {{{m, m, -m}, {-m, -m, m}, {m, -m, m}}},  // crosses the first
      {{{m, m, m}, {m - 1, m, m}, {m, m - 1, m}}},
      {{{m, m, m - 1}, {m - 1, m, m}, {m, m - 1, m}}},
  };
  const std::vector<ContactTriangle> ct = with_ids(tris);
  EXPECT_EQ(core::find_contacts(ct, 100).pairs, all_pairs_count(ct));
  EXPECT_GE(all_pairs_count(ct), 1u);
}

TEST(ContactSearch, FrameExtentsDismissARodsBoxPairsButNoPairThatMeets) {
  // A rod of slivers off the axes: the search takes its principal frame
  // (sliver_frame), whose extents dismiss most of the pairs that the boxes
  // and diagonals keep; every pair they dismiss has no common point (the
  // exact test says apart and no vertex is shared), and the search counts
  // exactly the pairs an all-pairs test finds, at any thread count. At the
  // origin and next to the grid's limit. An ordinary soup is not given a
  // frame.
  const std::int64_t far = kCoordLimit - 40000;
  for (const IntPoint& centre : {IntPoint{0, 0, 0}, IntPoint{far, -far, far}}) {
    const std::vector<Tri> tris = sliver_rod(600, centre, 41);
    const std::vector<ContactTriangle> ct = with_ids(tris);
    std::vector<core::Box32> boxes;
    for (const ContactTriangle& t : ct) boxes.push_back(core::box_of(t.p()));
    const core::TriangleTree tree(boxes);
    const std::optional<core::FrameAxes> frame = core::sliver_frame(ct, tree);
    ASSERT_TRUE(frame.has_value());
    std::size_t kept = 0, dismissed = 0;
    for (std::size_t i = 0; i < ct.size(); ++i)
      for (std::size_t j = i + 1; j < ct.size(); ++j) {
        if (!core::overlap(boxes[i], boxes[j]) ||
            core::diagonally_apart(core::diagonal_extent(ct[i].p()), core::diagonal_extent(ct[j].p())))
          continue;
        ++kept;
        if (!core::extents_apart(core::frame_extent(ct[i].p(), *frame), core::frame_extent(ct[j].p(), *frame)))
          continue;
        ++dismissed;
        EXPECT_FALSE(core::triangles_meet_improperly(ct[i], ct[j])) << i << ", " << j;
        for (const std::uint32_t a : ct[i].id)
          for (const std::uint32_t b : ct[j].id) EXPECT_NE(a, b) << i << ", " << j << " share a vertex";
      }
    EXPECT_GT(kept, 25u * ct.size()) << "the boxes and diagonals should keep dozens of pairs per triangle";
    EXPECT_GT(dismissed, kept / 2) << "the frame should dismiss most of them";
    const std::size_t expected = all_pairs_count(ct);
    EXPECT_GT(expected, 10u) << "some slivers should cross";
    for (const int threads : {1, 2, 4}) {
      tbb::task_arena arena(threads);
      core::ContactSearchResult r;
      arena.execute([&] { r = core::find_contacts(ct, std::size_t{1} << 30); });
      EXPECT_EQ(r.pairs, expected) << threads << " threads";
      EXPECT_TRUE(r.complete);
    }
  }
  const std::vector<Tri> soup = scattered(1500, 1000, 60, 5);
  const std::vector<ContactTriangle> ct = with_ids(soup);
  std::vector<core::Box32> boxes;
  for (const ContactTriangle& t : ct) boxes.push_back(core::box_of(t.p()));
  EXPECT_FALSE(core::sliver_frame(ct, core::TriangleTree(boxes)).has_value());
}

TEST(ContactSearch, ClosedSurfaceHasNoContacts) {
  const Mesh sphere = icosphere({0, 0, 0}, 1.0, 4);
  std::vector<Tri> tris;
  for (std::size_t f = 0; f < sphere.face_count(); ++f) {
    Tri t;
    for (int k = 0; k < 3; ++k) {
      const Vec3d& v = sphere.vertices[sphere.face(f)[k]];
      t[k] = {static_cast<std::int64_t>(v.x * 4096), static_cast<std::int64_t>(v.y * 4096),
              static_cast<std::int64_t>(v.z * 4096)};
    }
    if (!degenerate(t)) tris.push_back(t);
  }
  std::atomic<bool> found_one{false};
  const core::ContactSearchResult r = core::find_contacts(with_ids(tris), 1000, nullptr, &found_one);
  EXPECT_EQ(r.pairs, 0u);
  EXPECT_FALSE(r.gave_up);
  EXPECT_FALSE(found_one.load());  // the signal that stops a speculative solid path: never without a pair
}

TEST(ContactSearch, StopsAtMaxPairs) {
  const std::vector<Tri> corners = scattered(1500, 1000, 60, 1500);
  const std::vector<ContactTriangle> tris = with_ids(corners);
  ASSERT_GT(all_pairs_count(tris), 20u);
  std::atomic<bool> found_one{false};
  const core::ContactSearchResult r = core::find_contacts(tris, 20, nullptr, &found_one);
  EXPECT_EQ(r.pairs, 20u);
  EXPECT_FALSE(r.complete);  // a lower bound: the report says "at least"
  EXPECT_TRUE(found_one.load());
}

TEST(ContactSearch, GivesUpOnAPileOfParallelSlivers) {
  // Parallel, pairwise disjoint triangles whose boxes all overlap: n^2 / 2
  // box pairs, past the budget of about kBudgetPerTriangle * n. No pair
  // meets, so no verdict.
  const std::int64_t n = 2 * static_cast<std::int64_t>(core::kBudgetPerTriangle) + 1000;
  std::vector<Tri> tris;
  const std::int64_t w = 1 << 20;
  for (std::int64_t k = 0; k < n; ++k) tris.push_back({{{0, 0, k}, {w, 0, k + w}, {0, w, k}}});
  const core::ContactSearchResult r = core::find_contacts(with_ids(tris), 1000);
  EXPECT_EQ(r.pairs, 0u);
  EXPECT_TRUE(r.gave_up);
  // The same pile, small enough for the budget, is searched to the end.
  tris.resize(core::kBudgetPerTriangle / 2);
  const core::ContactSearchResult small = core::find_contacts(with_ids(tris), 1000);
  EXPECT_EQ(small.pairs, 0u);
  EXPECT_FALSE(small.gave_up);
  EXPECT_TRUE(small.complete);
}

TEST(ContactSearch, StopsCountingAPileOnceAPairDecides) {
  // The parallel pile of GivesUpOnAPileOfParallelSlivers with every eighth
  // triangle tilted up to a common far corner: each tilted one (the top of
  // its leaf of eight) crosses every plain triangle above it, so whatever
  // pair of distinct leaves the search (any thread count, any schedule)
  // examines first decides "not solid"; pairs within a leaf find none. The search
  // then only counts, and stops counting at kCountingPerTriangle box pairs
  // per triangle, far below its budget and before it has counted them all;
  // its count is a lower bound.
  const std::int64_t n = 2 * static_cast<std::int64_t>(core::kBudgetPerTriangle) + 1000;
  const std::int64_t w = 1 << 20;
  std::vector<Tri> tris;
  std::size_t crossing = 0, plain_above = 0;
  for (std::int64_t k = n - 1; k >= 0; --k) {  // top down, to count the plain ones above
    const bool tilted = k % 8 == 7;
    tris.push_back({{{0, 0, k}, {w, 0, k + w}, {0, w, tilted ? n + 10 : k}}});
    if (tilted) {
      crossing += plain_above;
    } else {
      ++plain_above;
    }
  }
  std::reverse(tris.begin(), tris.end());
  for (const int threads : {1, 2, 4}) {
    tbb::task_arena arena(threads);
    core::ContactSearchResult r;
    arena.execute([&] { r = core::find_contacts(with_ids(tris), std::size_t{1} << 30); });
    EXPECT_GT(r.pairs, 0u) << threads << " threads";
    EXPECT_LT(r.pairs, crossing) << threads << " threads";  // stopped counting
    EXPECT_FALSE(r.gave_up) << threads << " threads";       // a pair decided: a verdict
    EXPECT_FALSE(r.complete) << threads << " threads";
  }
  // Small enough to search to the end: every pair, counted completely.
  tris.resize(core::kCountingPerTriangle / 2);
  for (Tri& t : tris)
    if (t[2].z > n) t[2].z = static_cast<std::int64_t>(tris.size()) + 10;  // the small pile's own far corner
  const core::ContactSearchResult small = core::find_contacts(with_ids(tris), std::size_t{1} << 30);
  EXPECT_EQ(small.pairs, all_pairs_count(with_ids(tris)));
  EXPECT_GT(small.pairs, 0u);
  EXPECT_TRUE(small.complete);
}

}  // namespace
}  // namespace ember::test
