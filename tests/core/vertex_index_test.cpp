// The mesh stage's floating-point filter in front of its exact on-segment
// tests (core/mesh/vertex_index.hpp, clearly_off_segment): it must never rule
// out a point that lies exactly on the segment, whatever the scale of the
// caller's units, and it must rule out most points that do not.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "core/mesh/vertex_index.hpp"
#include "ember/core/quantize.hpp"
#include "ember/geometry/plane.hpp"
#include "ember/geometry/point.hpp"

namespace ember::core {
namespace {

TEST(VertexIndex, OffSegmentFilterNeverRulesOutAPointOnTheSegment) {
  std::mt19937_64 rng(3);
  const std::int64_t limit = Quantizer::kLimit;
  std::size_t on_segment = 0, ruled_out = 0, off_segment = 0;  // the last two in ordinary units only
  // Tiny, unit, huge and off-centre boxes: rounding errors relative to the
  // coordinates, not to the segment, are what the bound has to cover.
  const std::pair<Vec3d, Vec3d> boxes[] = {{{-1e-200, -1e-200, -1e-200}, {1e-200, 1e-200, 1e-200}},
                                           {{-1, -1, -1}, {1, 1, 1}},
                                           {{-1e200, -1e200, -1e200}, {1e200, 1e200, 1e200}},
                                           {{1e6, 1e6, 1e6}, {1e6 + 1, 1e6 + 1, 1e6 + 1}}};
  for (const auto& [lo, hi] : boxes) {
    const Quantizer q = Quantizer::fit_box(lo, hi);
    // At 1e+-200 the filter stands aside (its bounds assume no underflow or
    // overflow): it must still not rule out a point on the segment.
    const bool ordinary = std::fabs(hi.x) < 1e100 && std::fabs(hi.x) > 1e-100;
    for (int trial = 0; trial < 3000; ++trial) {
      // Short and long segments, anywhere in the grid.
      const std::int64_t range = trial % 2 ? limit : 1 + static_cast<std::int64_t>(rng() % 64);
      std::uniform_int_distribution<std::int64_t> at(-limit + range, limit - range), step(-range, range);
      const IntPoint base{at(rng), at(rng), at(rng)};
      const IntPoint a = base, b{base.x + step(rng), base.y + step(rng), base.z + step(rng)},
                     c{base.x + step(rng), base.y + step(rng), base.z + step(rng)};
      const std::optional<Plane> support = supporting_plane(a, b, c);
      if (!support) continue;
      // A point strictly inside a-b: the line a-b meets an axis plane between them.
      int axis = 0;
      while (axis < 2 && (axis == 0 ? a.x == b.x : axis == 1 ? a.y == b.y : a.z == b.z)) ++axis;
      const std::int64_t ca = axis == 0 ? a.x : axis == 1 ? a.y : a.z, cb = axis == 0 ? b.x : axis == 1 ? b.y : b.z;
      if (std::abs(cb - ca) < 2) continue;
      const std::int64_t t = std::min(ca, cb) + 1 + static_cast<std::int64_t>(rng() % static_cast<std::uint64_t>(std::abs(cb - ca) - 1));
      const std::optional<Point> v = intersect(*support, edge_plane(a, b, *support), axis_plane(axis, t));
      ASSERT_TRUE(v);
      const Vec3d ra = q.dequantize(a), rb = q.dequantize(b), rv = q.dequantize(*v), rc = q.dequantize(c);
      ++on_segment;
      ASSERT_FALSE(clearly_off_segment(ra, rb, rv)) << "a point on the segment was ruled out, trial " << trial;
      ASSERT_FALSE(clearly_off_segment(rb, ra, rv));
      // The third corner is off the line (the triangle has area).
      off_segment += ordinary;
      ruled_out += ordinary && clearly_off_segment(ra, rb, rc);
    }
  }
  EXPECT_GT(on_segment, 5000u);
  // The filter has to earn its place: most corners off the line are ruled
  // out (not all: off-centre short segments, 1e6 from the origin and a few
  // grid steps long, are within the rounding's reach of their third corner).
  EXPECT_GT(ruled_out, off_segment * 3 / 4);
}

}  // namespace
}  // namespace ember::core
