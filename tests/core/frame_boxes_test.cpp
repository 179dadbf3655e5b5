// Boxes in a pile leaf's principal frame (core/frame_boxes.hpp): a filter for
// gather that must never separate two polygons that share a point, and whose
// grid must return exactly the polygons whose frame boxes overlap.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <random>
#include <vector>

#include "core/frame_boxes.hpp"

namespace ember::core {
namespace {

using Tri = std::array<IntPoint, 3>;

/// Long thin triangles side by side along a diagonal (a strip pile), each
/// sharing its corners with its neighbours, at coordinates near the grid's
/// limit, plus triangles that touch a strip at one of its corners and
/// triangles whose corner is the midpoint of a strip's long edge (`contacts`:
/// pairs that touch although no corner is shared).
std::vector<Tri> strip_pile(std::int64_t origin, int strips, std::vector<std::array<std::size_t, 2>>* contacts = nullptr) {
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
    tris.push_back({c, IntPoint{c.x + off(), c.y + off(), c.z + 1 + (off() & 511)}, IntPoint{c.x + off(), c.y + off(), c.z - 1}});
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

Built build(std::vector<Tri> tris) {
  Built b;
  b.tris = std::move(tris);
  for (std::uint32_t i = 0; i < b.tris.size(); ++i) b.soup.push_back(unbuilt_triangle(b.tris[i], i, 0));
  approximate(b.soup, b.approx);
  return b;
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
  std::vector<std::uint32_t> got;
  std::size_t answered = 0, total = 0;
  for (std::size_t i = 0; i < b.tris.size(); ++i) {
    if (!frame.overlapping(i, queries[(i / 3) % 2], got)) continue;
    ++answered;
    std::vector<std::uint32_t> want;
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

TEST(FrameBoxes, ScanReturnsExactlyTheOverlappingBoxes) {
  // The strip pile plus 40 triangles spread along x: they swing the leaf's
  // principal direction, so here the strips come out wide (declined by the
  // grid, answered by scan) and the grid's wide pass is checked against
  // them; at small and at full-range coordinates. (A pile that the grid
  // separates is GridReturnsExactlyTheOverlappingBoxes's.)
  for (const std::int64_t origin : {std::int64_t{1000}, kCoordLimit - 2000000}) {
    std::vector<Tri> tris = strip_pile(origin, 200);
    for (int k = 0; k < 40; ++k) {
      const std::int64_t at = origin + 20000 * k;
      tris.push_back({IntPoint{at, origin, origin}, IntPoint{at + 5, origin + 900, origin + 3}, IntPoint{at, origin + 450, origin + 800}});
    }
    // And 40 small triangles astride the pile, spread along it: their boxes
    // meet strips' boxes, so the scan must find pairs across the two kinds.
    const std::size_t first_astride = tris.size();
    for (int k = 1; k <= 40; ++k) {
      const IntPoint c{origin + 400000 * k / 41, origin - 800000 * k / 41, origin + 80000 * k / 41};
      tris.push_back({IntPoint{c.x - 50, c.y, c.z - 40}, IntPoint{c.x + 900, c.y + 3, c.z}, IntPoint{c.x, c.y + 5, c.z + 40}});
    }
    const Built b = build(tris);
    const FrameBoxes frame(b.approx);
    FrameBoxes::Query query;
    std::vector<std::uint32_t> got, grid;
    std::size_t declined = 0, found = 0, astride_meets_pile = 0;
    for (std::size_t i = 0; i < b.tris.size(); ++i) {
      frame.scan(i, got);
      std::vector<std::uint32_t> want;
      for (std::uint32_t j = 0; j < b.tris.size(); ++j)
        if (j != i && !frame.apart(i, j)) want.push_back(j);
      ASSERT_EQ(got, want) << "polygon " << i;
      found += got.size();
      if (i >= first_astride) astride_meets_pile += std::count_if(got.begin(), got.end(), [](std::uint32_t j) { return j < 400; });
      if (frame.overlapping(i, query, grid)) {
        EXPECT_EQ(grid, got) << "polygon " << i;
      } else {
        ++declined;
      }
    }
    EXPECT_GT(declined, 0u);  // some polygons are scanned, not looked up
    EXPECT_GT(found, b.tris.size());
    EXPECT_LT(found, b.tris.size() * (b.tris.size() - 1));  // some boxes are apart: the scan filters
    EXPECT_GE(astride_meets_pile, 40u);                     // every astride triangle meets a strip's box
  }
}

}  // namespace
}  // namespace ember::core
