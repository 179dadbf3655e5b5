// Boxes in a pile leaf's principal frame (core/frame_boxes.hpp): a filter for
// gather that must never separate two polygons that share a point, and whose
// grid must return exactly the polygons whose frame boxes overlap.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <random>
#include <vector>

#include "core/route/general/frame_boxes.hpp"

namespace ember::core {
namespace {

using Tri = std::array<IntPoint, 3>;

/// Long thin triangles side by side along a diagonal (a strip pile), each
/// sharing its corners with its neighbours, at coordinates near the grid's
/// limit, plus triangles that touch a strip at one of its corners and
/// triangles whose corner is the midpoint of a strip's long edge (`contacts`:
/// pairs that touch although no corner is shared).
std::vector<Tri> strip_pile(std::int64_t origin, int strips,
                            std::vector<std::array<std::size_t, 2>>* contacts = nullptr) {
  std::vector<Tri> tris;
  const IntPoint dir{400000, -800000, 80000};  // the pile's direction (length ~9e5)
  for (int s = 0; s < strips; ++s) {
    // Strips wrap around a thin square tube, 4 grid units wide each.
    const std::int64_t lat = 4 * s;
    const IntPoint a{origin + lat, origin, origin + (s % 7)};
    const IntPoint b{origin + lat + 4, origin + 1, origin + ((s + 1) % 7)};
    const IntPoint far{a.x + dir.x, a.y + dir.y, a.z + dir.z};
    const IntPoint far_b{b.x + dir.x, b.y + dir.y, b.z + dir.z};
    tris.push_back({a, b, far});
    tris.push_back({b, far_b, far});
  }
  std::mt19937_64 rng(7);
  for (int k = 0; k < 40; ++k) {
    const Tri& t = tris[rng() % tris.size()];
    const IntPoint& c = t[rng() % 3];
    const auto off = [&] { return static_cast<std::int64_t>(rng() % 2001) - 1000; };
    tris.push_back(
        {c, IntPoint{c.x + off(), c.y + off(), c.z + 1 + (off() & 511)}, IntPoint{c.x + off(), c.y + off(), c.z - 1}});
  }
  for (int k = 0; contacts && k < 400; ++k) {
    const std::size_t s = 2 * (rng() % static_cast<std::size_t>(strips));  // a strip's first triangle: a, b, far
    const Tri& t = tris[s];
    const IntPoint m{(t[0].x + t[2].x) / 2, (t[0].y + t[2].y) / 2, (t[0].z + t[2].z) / 2};  // on edge far-a
    const auto off = [&] { return static_cast<std::int64_t>(rng() % 2001) - 1000; };
    contacts->push_back({s, tris.size()});
    tris.push_back({m, IntPoint{m.x + off(), m.y + off(), m.z + 3000}, IntPoint{m.x + off(), m.y + 1500, m.z - 3000}});
  }
  return tris;
}

struct Built {
  std::vector<Tri> tris;
  Soup soup;
  SoupApprox approx;
};

/// The soup of `tris`, triangle i of operand operand[i] (0 for all without).
Built build(std::vector<Tri> tris, const std::vector<std::uint32_t>& operand = {}) {
  Built b;
  b.tris = std::move(tris);
  for (std::uint32_t i = 0; i < b.tris.size(); ++i)
    b.soup.push_back(unbuilt_triangle(b.tris[i], i, operand.empty() ? 0 : operand[i]));
  approximate(b.soup, b.approx);
  return b;
}

using Ids = FrameBoxes::Candidates;

/// Every way of scanning answers `want` for polygon i: the scan that runs
/// here, its portable and its four-lane versions, and candidates() (the
/// scan or the grid, whichever `frame` takes for i).
void expect_scans_answer(const FrameBoxes& frame, std::size_t i, const Ids& want) {
  FrameBoxes::Query query;
  Ids got;
  frame.scan(i, got);
  EXPECT_EQ(got, want) << "scan, polygon " << i;
  frame.scan_portable(i, got);
  EXPECT_EQ(got, want) << "portable scan, polygon " << i;
#if EMBER_WIDE_LANES
  if (cpu_has_avx2()) {
    frame.scan_avx2(i, got);
    EXPECT_EQ(got, want) << "four-lane scan, polygon " << i;
  }
#endif
  frame.candidates(i, query, got);
  EXPECT_EQ(got, want) << "candidates, polygon " << i;
}

bool share_corner(const Tri& a, const Tri& b) {
  for (const IntPoint& p : a)
    for (const IntPoint& q : b)
      if (p == q) return true;
  return false;
}

TEST(FrameBoxes, PolygonsSharingAPointAreNeverApart) {
  for (const std::int64_t origin : {std::int64_t{0}, std::int64_t{-16000000}, std::int64_t{15000000}}) {
    std::vector<std::array<std::size_t, 2>> contacts;
    const Built b = build(strip_pile(origin, 200, &contacts));
    FrameBoxes frame(b.approx);
    ASSERT_FALSE(frame.empty());
    for (const auto& [i, j] : contacts) {
      EXPECT_FALSE(frame.apart(i, j)) << "triangle " << j << " has a corner on an edge of " << i;
      EXPECT_FALSE(frame.apart(j, i));
    }
    std::size_t touching = 0;
    for (std::size_t i = 0; i < b.tris.size(); ++i)
      for (std::size_t j = 0; j < b.tris.size(); ++j)
        if (i != j && share_corner(b.tris[i], b.tris[j])) {
          ++touching;
          EXPECT_FALSE(frame.apart(i, j)) << "triangles " << i << " and " << j << " share a corner";
        }
    EXPECT_GT(touching, 400u);
  }
}

TEST(FrameBoxes, GridReturnsExactlyTheOverlappingBoxes) {
  const Built b = build(strip_pile(1000, 300));
  const FrameBoxes frame(b.approx);
  // Two callers' queries interleaved, as threads share one pile leaf's frame:
  // each query's memory of what it found is its own.
  std::array<FrameBoxes::Query, 2> queries;
  Ids got;
  std::size_t answered = 0, total = 0;
  for (std::size_t i = 0; i < b.tris.size(); ++i) {
    if (!frame.overlapping(i, queries[(i / 3) % 2], got)) continue;
    ++answered;
    Ids want;
    for (std::uint32_t j = 0; j < b.tris.size(); ++j)
      if (j != i && !frame.apart(i, j)) want.push_back(j);
    EXPECT_EQ(got, want) << "polygon " << i;
    total += got.size();
  }
  // The strips separate across the pile: most polygons are answered from the
  // grid, with few candidates each (their axis-aligned boxes all overlap).
  EXPECT_GT(answered, b.tris.size() / 2);
  EXPECT_LT(total, answered * b.tris.size() / 10);
}

/// A bundle of parallel needles along the diagonal `dir`, one per point of
/// a 32 x 32 lattice (100 units apart) across it, each with the short side
/// `base`: by default each needle's frame box is thin across the bundle, as
/// the grid's cells are (one needle column per cell).
std::vector<Tri> needle_bundle(std::int64_t origin, const IntPoint& dir, const IntPoint& base = {2, 1, 1}) {
  std::vector<Tri> tris;
  for (int a = 0; a < 32; ++a)
    for (int b = 0; b < 32; ++b) {
      const IntPoint p{origin + 100 * a, origin, origin + 100 * b};
      tris.push_back(
          {p, IntPoint{p.x + base.x, p.y + base.y, p.z + base.z}, IntPoint{p.x + dir.x, p.y + dir.y, p.z + dir.z}});
    }
  return tris;
}

TEST(FrameBoxes, ScanReturnsExactlyTheOverlappingBoxes) {
  // The needle bundle plus 12 triangles across it, each covering the whole
  // cross-section at one point along it: they are few, so the grid stays
  // fine for the needles, and wide, so the grid declines them (scan answers)
  // and its wide pass must find them for every needle they meet; at small
  // and at full-range coordinates. Every answer is checked against testing
  // all pairs.
  const IntPoint dir{400000, -800000, 80000};
  for (const std::int64_t origin : {std::int64_t{1000}, kCoordLimit - 2000000}) {
    std::vector<Tri> tris = needle_bundle(origin, dir);
    const std::size_t needles = tris.size();
    for (int k = 1; k <= 12; ++k) {
      const IntPoint c{origin + dir.x * k / 13, origin + dir.y * k / 13, origin + dir.z * k / 13};
      tris.push_back({IntPoint{c.x - 500, c.y - 1000, c.z - 500}, IntPoint{c.x + 7000, c.y + 1000, c.z - 400},
                      IntPoint{c.x - 400, c.y + 2000, c.z + 7000}});
    }
    const Built b = build(tris);
    const FrameBoxes frame(b.approx);
    // Thin needles: the grid stays at its finest (one needle column per cell).
    EXPECT_EQ(frame.grid_cells()[0], 32);
    EXPECT_EQ(frame.grid_cells()[1], 32);
    FrameBoxes::Query query;
    Ids got, grid;
    std::size_t declined = 0, answered_pairs = 0, wide_meets_needle = 0;
    // A fine grid: candidates() asks it (and scans what it declines).
    EXPECT_FALSE(frame.scans_first());
    for (std::size_t i = 0; i < b.tris.size(); ++i) {
      Ids want;
      for (std::uint32_t j = 0; j < b.tris.size(); ++j)
        if (j != i && !frame.apart(i, j)) want.push_back(j);
      expect_scans_answer(frame, i, want);
      frame.scan(i, got);
      if (i >= needles)
        wide_meets_needle += std::count_if(got.begin(), got.end(), [&](std::uint32_t j) { return j < needles; });
      if (frame.overlapping(i, query, grid)) {
        EXPECT_EQ(grid, got) << "polygon " << i;
        // The needles' answers include the wide triangles they meet (the
        // grid's wide pass), not only their cells' members.
        answered_pairs += static_cast<std::size_t>(
            std::count_if(grid.begin(), grid.end(), [&](std::uint32_t j) { return j >= needles; }));
      } else {
        ++declined;
      }
    }
    EXPECT_GE(declined, 12u);           // the wide triangles are scanned, not looked up
    EXPECT_LT(declined, needles / 2);   // the needles are looked up
    EXPECT_GT(wide_meets_needle, 12u);  // each wide triangle meets needles' boxes
    EXPECT_GT(answered_pairs, 12u);     // ... which the grid's answers for the needles include
  }
}

TEST(FrameBoxes, CoarsenedGridReturnsExactlyTheOverlappingBoxes) {
  const IntPoint dir{400000, -800000, 80000};
  for (const std::int64_t origin : {std::int64_t{1000}, kCoordLimit - 2000000}) {
    // Broad needles: each covers about six lattice columns each way, so a
    // grid of one column per cell would mark each member ~40 times per query.
    // The whole bundle and bundles short of one to three needles: the
    // four-lane scan tests the last group of fewer than four one by one.
    const std::vector<Tri> bundle = needle_bundle(origin, dir, {600, 1, 600});
    for (std::size_t n = bundle.size(); n + 4 > bundle.size(); --n) {
      const Built b = build({bundle.begin(), bundle.begin() + static_cast<std::ptrdiff_t>(n)});
      const FrameBoxes frame(b.approx);
      // Coarsened from 32 cells per axis until a polygon covers about 4:
      // candidates() scans where four boxes go in one compare.
      EXPECT_LE(frame.grid_cells()[0], 8);
      EXPECT_LE(frame.grid_cells()[1], 8);
      EXPECT_EQ(frame.scans_first(), cpu_has_avx2());
      FrameBoxes::Query query;
      Ids got;
      std::size_t answered = 0;
      for (std::size_t i = 0; i < n; ++i) {
        Ids want;
        for (std::uint32_t j = 0; j < n; ++j)
          if (j != i && !frame.apart(i, j)) want.push_back(j);
        expect_scans_answer(frame, i, want);
        if (!frame.overlapping(i, query, got)) continue;  // none is wide on a coarse grid
        ++answered;
        ASSERT_EQ(got, want) << "polygon " << i;
      }
      EXPECT_EQ(answered, n);
    }
  }
}

/// Pairs (i, j), i != j, whose boxes the frame does not hold apart.
std::size_t pairs_not_apart(const FrameBoxes& frame, std::size_t n) {
  std::size_t pairs = 0;
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = 0; j < n; ++j) pairs += i != j && !frame.apart(i, j);
  return pairs;
}

TEST(FrameBoxes, OperandFramesSeparateTwoBundlesAtASmallAngle) {
  // Two operands' needle bundles through the same tube, 0.3 degrees apart
  // (the sliver pile's twin rods): in the leaf's frame, between the two,
  // each needle drifts across ~2,300 units of the 3,100-unit section. Plus
  // triangles of operand 1 that touch operand 0's needles without sharing a
  // corner (a corner on a needle's long edge) or at its tip.
  const IntPoint dir{400000, -800000, 80000}, tilt{0, 0, 4600};
  for (const std::int64_t origin : {std::int64_t{1000}, kCoordLimit - 2000000}) {
    std::vector<Tri> tris = needle_bundle(origin, dir);
    const std::size_t first = tris.size();
    for (const Tri& t : needle_bundle(origin, IntPoint{dir.x + tilt.x, dir.y + tilt.y, dir.z + tilt.z}))
      tris.push_back(t);
    std::vector<std::uint32_t> operand(tris.size(), 1);
    std::fill(operand.begin(), operand.begin() + static_cast<std::ptrdiff_t>(first), 0);
    std::vector<std::array<std::size_t, 2>> contacts;
    std::mt19937_64 rng(11);
    // 303 of them: 2,351 polygons, not a multiple of four (the four-lane
    // scan's last group).
    for (int k = 0; k < 303; ++k) {
      const std::size_t s = rng() % first;
      const Tri& t = tris[s];
      const IntPoint on_edge{(t[0].x + t[2].x) / 2, (t[0].y + t[2].y) / 2, (t[0].z + t[2].z) / 2};
      const IntPoint m = k % 2 ? on_edge : t[2];  // the needle's edge (exactly on it: even offsets) or its tip
      contacts.push_back({s, tris.size()});
      tris.push_back({m, IntPoint{m.x + 700, m.y + 40, m.z + 300}, IntPoint{m.x - 90, m.y + 800, m.z - 500}});
      operand.push_back(1);
    }
    // The edge midpoints are grid points on the edge: dir is even.
    static_assert(400000 % 2 == 0 && 800000 % 2 == 0 && 80000 % 2 == 0);
    const Built b = build(tris, operand);
    const FrameBoxes leaf_only(b.approx), with_operands(b.approx, operand);
    EXPECT_FALSE(leaf_only.has_operand_frames());
    ASSERT_TRUE(with_operands.has_operand_frames());
    for (const auto& [i, j] : contacts) {
      EXPECT_FALSE(with_operands.apart(i, j)) << "triangle " << j << " touches needle " << i;
      EXPECT_FALSE(with_operands.apart(j, i));
    }
    // The operands' frames hold about half of the leaf frame's pairs apart
    // (209,964 -> 104,636: what is left are mostly needles of the two
    // operands that really cross in the section), and never bring a pair the
    // leaf frame holds apart together again (below).
    const std::size_t leaf_pairs = pairs_not_apart(leaf_only, tris.size());
    const std::size_t both_pairs = pairs_not_apart(with_operands, tris.size());
    EXPECT_LT(both_pairs, leaf_pairs * 6 / 10) << leaf_pairs << " pairs in the leaf's frame";
    // The grid's and the scan's answers are exactly the pairs not apart.
    FrameBoxes::Query query;
    Ids got;
    for (std::size_t i = 0; i < tris.size(); ++i) {
      Ids want;
      for (std::uint32_t j = 0; j < tris.size(); ++j)
        if (j != i && !with_operands.apart(i, j)) {
          want.push_back(j);
          EXPECT_FALSE(leaf_only.apart(i, j));
        }
      expect_scans_answer(with_operands, i, want);
      if (with_operands.overlapping(i, query, got)) {
        ASSERT_EQ(got, want) << "polygon " << i;
      }
    }
  }
}

}  // namespace
}  // namespace ember::core
