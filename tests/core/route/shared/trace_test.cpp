// Traces over a root soup (core/trace.hpp: scan_soup) add their crossings in
// parallel chunks: the sums and the verdict must be those of one serial pass
// of the exact per-polygon test, at any thread count.
#include <gtest/gtest.h>
#include <tbb/task_arena.h>

#include <random>
#include <vector>

#include "core/route/general/subproblem.hpp"
#include "core/route/general/leaf.hpp"
#include "core/route/shared/trace.hpp"

namespace ember::core {
namespace {

IntPoint random_point(std::mt19937_64& rng, std::int64_t range) {
  std::uniform_int_distribution<std::int64_t> c(-range, range);
  return {c(rng), c(rng), c(rng)};
}

/// The exact answer: every polygon whose box the segment meets, tested on
/// its own, in soup order (no miss filters, no chunks).
bool serial_trace(const Soup& soup, const Dyadic& a, const Dyadic& b, int axis, Wnv& w) {
  AxisSegment seg;
  if (!make_axis_segment(a, b, axis, seg)) return true;
  for (const SoupPolygon& p : soup)
    if (!box_disjoint(p, seg.lo, seg.hi) && !add_crossing(seg, p, w)) return false;
  return true;
}

TEST(Trace, RootSoupScanSumsLikeOneSerialPass) {
  constexpr std::size_t kTriangles = 100000;  // above scan_soup's parallel threshold (2^16)
  constexpr std::int64_t kRange = 200;
  std::mt19937_64 rng(5);
  std::vector<std::array<IntPoint, 3>> corners(kTriangles);
  Soup soup;
  soup.reserve(kTriangles);
  for (std::uint32_t i = 0; i < kTriangles; ++i) {
    do {
      corners[i] = {random_point(rng, kRange), random_point(rng, kRange), random_point(rng, kRange)};
    } while (grid_normal(corners[i][0], corners[i][1], corners[i][2]) == std::array<std::int64_t, 3>{0, 0, 0});
    soup.push_back(unbuilt_triangle(corners[i], i, i % 3));
  }
  // Segments between half-integer points (odd numerators over 2): they miss
  // the grid points, so most cross edges nowhere and have a verdict with sums.
  std::uniform_int_distribution<std::int64_t> odd(-kRange, kRange);
  std::size_t traced = 0, crossings = 0;
  for (int s = 0; s < 40; ++s) {
    const int axis = s % 3;
    Dyadic a{{2 * odd(rng) + 1, 2 * odd(rng) + 1, 2 * odd(rng) + 1}, 1};
    Dyadic b = a;
    b.num[axis] = 2 * odd(rng) + 1;
    Wnv want(3, 0);
    const bool ok = serial_trace(soup, a, b, axis, want);
    for (const int threads : {1, 4}) {
      Wnv got(3, 0);
      bool got_ok = false;
      tbb::task_arena(threads).execute([&] { got_ok = trace_axis_segment(soup, a, b, axis, got); });
      ASSERT_EQ(got_ok, ok) << "segment " << s << ", " << threads << " threads";
      if (ok) {
        EXPECT_EQ(got, want) << "segment " << s << ", " << threads << " threads";
      }
    }
    if (ok) {
      ++traced;
      for (const int v : want) crossings += static_cast<std::size_t>(v < 0 ? -v : v);
    }
  }
  // The check means something: most segments get a verdict, and they cross a lot.
  EXPECT_GT(traced, 20u);
  EXPECT_GT(crossings, 100u);
}

/// The proof's classification (classify_polygon: a path, then the last
/// segment onto the piece, whose coplanar polygons at the target add to
/// `delta`) over a root soup that scan_soup splits into chunks must be the
/// one over the same polygons without the far filler that makes it large.
TEST(Trace, ClassificationOverARootSoupIsTheSerialOne) {
  std::mt19937_64 rng(9);
  std::vector<std::array<IntPoint, 3>> tris;  // the near triangles, then the filler
  // A stack of coplanar copies of one triangle, some turned over, then
  // triangles across the region the paths go through.
  for (int k = 0; k < 12; ++k)
    tris.push_back(k % 3 == 2 ? std::array<IntPoint, 3>{{{0, 0, 0}, {0, 100, 0}, {100, 0, 0}}}
                              : std::array<IntPoint, 3>{{{0, 0, 0}, {100, 0, 0}, {0, 100, 0}}});
  while (tris.size() < 400) {
    const std::array<IntPoint, 3> c{random_point(rng, 120), random_point(rng, 120), random_point(rng, 120)};
    if (grid_normal(c[0], c[1], c[2]) != std::array<std::int64_t, 3>{0, 0, 0}) tris.push_back(c);
  }
  const std::size_t near = tris.size();
  // The filler lies beyond x = 10000, where no path between the reference
  // point (at the low corner) and the near triangles goes.
  while (tris.size() < 70000) {
    IntPoint o = random_point(rng, 100);
    o.x += 10100;
    tris.push_back({o, IntPoint{o.x + 3, o.y, o.z + 1}, IntPoint{o.x, o.y + 2, o.z + 5}});
  }
  const auto root = [&](std::size_t count) {
    Subproblem pb;
    pb.box.lo = {-200, -200, -200};  // the same box (and reference point) for both soups
    pb.box.hi = {10400, 200, 200};
    for (int a = 0; a < 3; ++a) pb.ref.num[a] = 2 * pb.box.lo[a] + 1;
    pb.ref.shift = 1;
    pb.ref_w.assign(3, 0);
    for (std::uint32_t i = 0; i < count; ++i) pb.soup.push_back(unbuilt_triangle(tris[i], i, i % 3));
    return pb;
  };
  const Subproblem small_pb = root(near), big_pb = root(tris.size());
  std::size_t classified = 0;
  for (std::uint32_t t = 0; t < 60; ++t) {
    Wnv front, back;
    const bool ok = classify_polygon(small_pb, small_pb.soup[t], front, back);
    for (const int threads : {1, 4}) {
      Wnv big_front, big_back;
      bool big_ok = false;
      tbb::task_arena(threads).execute([&] { big_ok = classify_polygon(big_pb, big_pb.soup[t], big_front, big_back); });
      ASSERT_EQ(big_ok, ok) << "triangle " << t << ", " << threads << " threads";
      if (ok) {
        EXPECT_EQ(big_front, front) << "triangle " << t << ", " << threads << " threads";
        EXPECT_EQ(big_back, back) << "triangle " << t << ", " << threads << " threads";
      }
    }
    classified += ok;
  }
  EXPECT_GT(classified, 40u);
  // The stack's copies see each other at their common target: front and back differ by the stack's sum.
  Wnv front, back;
  ASSERT_TRUE(classify_polygon(big_pb, big_pb.soup[0], front, back));
  EXPECT_NE(front, back);
}

}  // namespace
}  // namespace ember::core
