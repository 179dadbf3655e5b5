// The reduced-width axis-line test must give exactly the answers of the
// general (oracle-tested) intersect_segment on the same line.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "geometry/geometry.hpp"

namespace ember::test {
namespace {

Plane dyadic_plane(int axis, __int128 num, int shift) {
  Plane p{0, 0, 0, -num};
  (axis == 0 ? p.a : axis == 1 ? p.b : p.c) = std::int64_t{1} << shift;
  return p;
}

struct Case {
  AxisLine line;
  Plane l0, l1, r0, r1;
};

/// A segment along `axis` through (U, V)/2^s from coordinate lo to hi.
Case make_case(int axis, __int128 U, __int128 V, int s, __int128 lo, __int128 hi) {
  Case c;
  c.line = {axis, DyadicNum(U), DyadicNum(V), s};
  c.l0 = dyadic_plane((axis + 1) % 3, U, s);
  c.l1 = dyadic_plane((axis + 2) % 3, V, s);
  c.r0 = -dyadic_plane(axis, lo, s);  // x >= lo
  c.r1 = dyadic_plane(axis, hi, s);   // x <= hi
  return c;
}

void expect_same(const Case& c, const Polygon& poly) {
  const SegmentHit general = intersect_segment(c.l0, c.l1, c.r0, c.r1, poly, nullptr);
  const SegmentHit fast = intersect_segment(c.line, c.r0, c.r1, poly);
  ASSERT_EQ(static_cast<int>(general.kind), static_cast<int>(fast.kind));
  if (general.kind != LineHit::InPlane) {
    ASSERT_EQ(general.at_endpoint, fast.at_endpoint);
  }
}

TEST(AxisLine, MatchesGeneralSegmentTestOnRandomTriangles) {
  std::mt19937_64 rng(42);
  const std::int64_t L = kCoordLimit;
  std::uniform_int_distribution<std::int64_t> coord(-L, L);
  int interior = 0, boundary = 0, endpoint = 0;
  for (int it = 0; it < 4000; ++it) {
    const IntPoint p[3] = {{coord(rng), coord(rng), coord(rng)},
                           {coord(rng), coord(rng), coord(rng)},
                           {coord(rng), coord(rng), coord(rng)}};
    const std::optional<Polygon> tri = make_triangle(p[0], p[1], p[2]);
    if (!tri) continue;
    const int axis = static_cast<int>(rng() % 3);
    const int u = (axis + 1) % 3, v = (axis + 2) % 3;
    auto get = [](const IntPoint& q, int a) { return static_cast<__int128>(a == 0 ? q.x : (a == 1 ? q.y : q.z)); };
    const int s = static_cast<int>(rng() % 53);
    __int128 U, V;
    if (it % 3 == 0) {  // through a vertex: exact boundary hits
      U = get(p[it % 3], u) << s;
      V = get(p[it % 3], v) << s;
    } else {  // through the centroid, rounded to the dyadic grid
      U = ((get(p[0], u) + get(p[1], u) + get(p[2], u)) << s) / 3;
      V = ((get(p[0], v) + get(p[1], v) + get(p[2], v)) << s) / 3;
    }
    // Segment ends: sometimes exactly at a vertex's height (endpoint hits).
    __int128 lo = static_cast<__int128>(-L) << s, hi = static_cast<__int128>(L) << s;
    if (it % 5 == 0) hi = get(p[it % 3], axis) << s;
    const Case c = make_case(axis, U, V, s, lo, hi);
    expect_same(c, *tri);
    const SegmentHit h = intersect_segment(c.line, c.r0, c.r1, *tri);
    interior += h.kind == LineHit::Interior;
    boundary += h.kind == LineHit::Boundary;
    endpoint += h.at_endpoint;
  }
  // The generator must exercise every outcome, or the comparison proves little.
  EXPECT_GT(interior, 100);
  EXPECT_GT(boundary, 100);
  EXPECT_GT(endpoint, 10);
}

TEST(AxisLine, FilteredClassifyMatchesExactNearPlanes) {
  // The meeting point lies exactly on the support: the support shifted by d+-1
  // is as close as a plane can get, where only the exact path can decide.
  std::mt19937_64 rng(8);
  const std::int64_t L = kCoordLimit;
  std::uniform_int_distribution<std::int64_t> coord(-L, L);
  int checked = 0;
  for (int it = 0; it < 3000; ++it) {
    const std::optional<Plane> s =
        supporting_plane({coord(rng), coord(rng), coord(rng)}, {coord(rng), coord(rng), coord(rng)},
                         {coord(rng), coord(rng), coord(rng)});
    if (!s) continue;
    const int shift = static_cast<int>(rng() % 53);
    const AxisLine line{static_cast<int>(rng() % 3), DyadicNum(static_cast<__int128>(coord(rng)) << shift),
                        DyadicNum(static_cast<__int128>(coord(rng)) << shift), shift};
    AxisPoint x;
    if (!meet(line, *s, x)) continue;
    EXPECT_EQ(classify(x, *s), 0);
    for (int delta : {-1, 1}) {
      Plane t = *s;
      t.d = OffsetCoef::assume_bound(t.d + OffsetCoef(delta));
      EXPECT_EQ(classify(x, t), delta);  // exactly +-1 at x
      EXPECT_EQ(classify_exact(x, t), delta);
      ++checked;
    }
  }
  EXPECT_GT(checked, 4000);
}

/// A point on the segment a -> b at parameter num/den, on the 2^s grid of the
/// line's plane coordinates (u, v).
std::array<__int128, 2> on_segment(const Point& a, const Point& b, int u, int v, int s, double t) {
  const auto& fa = a.f;
  const auto& fb = b.f;
  return {static_cast<__int128>(std::nearbyint(std::ldexp(fa[u] + t * (fb[u] - fa[u]), s))),
          static_cast<__int128>(std::nearbyint(std::ldexp(fa[v] + t * (fb[v] - fa[v]), s)))};
}

TEST(AxisLine, ClearMissFilterNeverContradictsTheExactTest) {
  // Clipped triangles at full coordinate range (vertices with large w, so the
  // cached doubles carry their full error) against lines through points at,
  // just inside and just outside their edges, at every dyadic resolution.
  std::mt19937_64 rng(2022);
  std::uniform_int_distribution<std::int64_t> coord(-kCoordLimit, kCoordLimit);
  const auto point = [&] { return IntPoint{coord(rng), coord(rng), coord(rng)}; };
  int filtered = 0, exact_misses = 0, checked = 0;
  for (int it = 0; it < 3000; ++it) {
    const IntPoint p[6] = {point(), point(), point(), point(), point(), point()};
    const std::optional<Polygon> tri = make_triangle(p[0], p[1], p[2]);
    if (!tri) continue;
    Polygon poly = *tri, neg, pos;
    const std::optional<Plane> cut = supporting_plane(p[3], p[4], p[5]);
    if (cut && clip(*tri, *cut, neg, pos) == ClipSide::Both) poly = it % 2 ? neg : pos;
    const int axis = static_cast<int>(rng() % 3), u = (axis + 1) % 3, v = (axis + 2) % 3;
    if (poly.support.normal(axis).is_zero()) continue;
    const std::size_t e = rng() % poly.size();
    const int s = static_cast<int>(rng() % 53);
    const double t = std::uniform_real_distribution<double>(0.0, 1.0)(rng);
    const auto at = on_segment(poly.vertices[e], poly.vertices[(e + 1) % poly.size()], u, v, s, t);
    for (const int du : {-3, -1, 0, 1, 3})
      for (const int dv : {-3, -1, 0, 1, 3}) {
        // Offsets of a few 2^-s steps, or far outside (a clear miss).
        const __int128 scale = (it % 4 == 0) ? (static_cast<__int128>(1) << (s + 20)) : 1;
        const AxisLine line{axis, DyadicNum(at[0] + du * scale), DyadicNum(at[1] + dv * scale), s};
        AxisPoint x;
        ASSERT_TRUE(meet(line, poly.support, x));
        const bool miss = locate(poly, x) > 0;
        const bool says_miss = line_clearly_misses(line, line_point_approx(line), poly);
        if (says_miss) {
          ASSERT_TRUE(miss) << "the filter claimed a miss the exact test denies";
        }
        filtered += says_miss;
        exact_misses += miss;
        ++checked;
      }
  }
  // Both outcomes must occur often, or the comparison proves little.
  EXPECT_GT(checked, 50000);
  EXPECT_GT(filtered, 5000);
  EXPECT_GT(exact_misses - filtered, 1000);  // near-edge misses left to the exact test
}

TEST(AxisLine, ParallelAndInPlaneLines) {
  const Polygon tri = *make_triangle({0, 0, 0}, {12, 0, 0}, {0, 12, 0});  // z = 0
  // Along x at z = 0 (in the plane) and at z = 1/2 (parallel, off it).
  expect_same(make_case(0, 3, 0, 0, -20, 20), tri);
  EXPECT_EQ(intersect_segment(AxisLine{0, DyadicNum(3), DyadicNum(0), 0}, -dyadic_plane(0, -20, 0),
                              dyadic_plane(0, 20, 0), tri)
                .kind,
            LineHit::InPlane);
  EXPECT_EQ(intersect_segment(AxisLine{0, DyadicNum(3), DyadicNum(1), 1}, -dyadic_plane(0, -40, 1),
                              dyadic_plane(0, 40, 1), tri)
                .kind,
            LineHit::Miss);
  // Along z through (1/4, 1/4): interior; through (6, 6): the hypotenuse.
  EXPECT_EQ(
      intersect_segment(AxisLine{2, DyadicNum(1), DyadicNum(1), 2}, -dyadic_plane(2, -8, 2), dyadic_plane(2, 8, 2), tri)
          .kind,
      LineHit::Interior);
  EXPECT_EQ(
      intersect_segment(AxisLine{2, DyadicNum(6), DyadicNum(6), 0}, -dyadic_plane(2, -8, 0), dyadic_plane(2, 8, 0), tri)
          .kind,
      LineHit::Boundary);
}

}  // namespace
}  // namespace ember::test
