// Traces over a root soup (core/trace.hpp: scan_soup) add their crossings in
// parallel chunks: the sums and the verdict must be those of one serial pass
// of the exact per-polygon test, at any thread count.
#include <gtest/gtest.h>
#include <tbb/task_arena.h>

#include <random>
#include <vector>

#include "core/trace.hpp"

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

}  // namespace
}  // namespace ember::core
