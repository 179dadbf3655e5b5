// Clipping invariants: exact partition of the area, exact incidence of every
// vertex, exactly two vertices on the split plane, and the degenerate cases.
#include <gtest/gtest.h>

#include "support/polygon_check.hpp"

namespace ember::test {
namespace {

/// Clips and checks everything that must hold; returns the side.
ClipSide clip_and_check(const Polygon& poly, const Plane& split, Polygon& neg, Polygon& pos) {
  const ClipSide side = clip(poly, split, neg, pos);
  // Reference side from the exact vertex classification.
  bool has_neg = false, has_pos = false;
  for (const Point& v : poly.vertices) {
    const int s = sign_of(dot(to_mp(split), to_mp(v)));
    has_neg |= s < 0;
    has_pos |= s > 0;
  }
  const ClipSide expect = has_neg && has_pos ? ClipSide::Both
                          : has_pos          ? ClipSide::Positive
                          : has_neg          ? ClipSide::Negative
                                             : ClipSide::On;
  EXPECT_EQ(side, expect);
  if (side != ClipSide::Both) return side;
  EXPECT_TRUE(check_polygon(neg));
  EXPECT_TRUE(check_polygon(pos));
  EXPECT_TRUE(neg.support == poly.support);
  EXPECT_TRUE(pos.support == poly.support);
  // Each part lies on its side, with exactly two vertices on the plane.
  int zn = 0, zp = 0;
  for (const Point& v : neg.vertices) {
    EXPECT_LE(classify(v, split), 0);
    zn += classify(v, split) == 0;
  }
  for (const Point& v : pos.vertices) {
    EXPECT_GE(classify(v, split), 0);
    zp += classify(v, split) == 0;
  }
  EXPECT_EQ(zn, 2);
  EXPECT_EQ(zp, 2);
  // The split plane is an edge of each part, oriented outward.
  EXPECT_EQ(std::count(neg.edges.begin(), neg.edges.end(), split), 1);
  EXPECT_EQ(std::count(pos.edges.begin(), pos.edges.end(), -split), 1);
  // The parts partition the polygon: projected areas add up exactly, same sign.
  const mpq_class whole = projected_area2(poly), a = projected_area2(neg), b = projected_area2(pos);
  EXPECT_EQ(a + b, whole);
  EXPECT_EQ(sgn(a), sgn(whole));
  EXPECT_EQ(sgn(b), sgn(whole));
  return side;
}

TEST(GeometryClip, RandomTrianglesByCuttingAxisPlanes) {
  Gen g(30);
  Polygon neg, pos;
  int both = 0;
  for (int i = 0; i < 3000; ++i) {
    const auto t =
        (i % 3) ? g.triangle() : std::array<IntPoint, 3>{g.small_point(6), g.small_point(6), g.small_point(6)};
    const auto tri = make_triangle(t[0], t[1], t[2]);
    if (!tri) continue;
    const int axis = static_cast<int>(g.uniform(0, 2));
    const std::int64_t c[3] = {(&t[0].x)[axis], (&t[1].x)[axis], (&t[2].x)[axis]};
    // Positions within the triangle's extent, including exactly through vertices.
    const std::int64_t pos_at =
        (i % 4 == 0) ? c[i % 3] : g.uniform(*std::min_element(c, c + 3), *std::max_element(c, c + 3));
    const Plane split = (i % 2) ? axis_plane(axis, pos_at) : -axis_plane(axis, pos_at);
    both += clip_and_check(*tri, split, neg, pos) == ClipSide::Both;
  }
  EXPECT_GT(both, 1500);
}

TEST(GeometryClip, RandomTrianglesBySupportingAndEdgePlanes) {
  Gen g(31);
  Polygon neg, pos;
  int both = 0;
  for (int i = 0; i < 3000; ++i) {
    const auto t = g.triangle();
    const auto tri = make_triangle(t[0], t[1], t[2]);
    ASSERT_TRUE(tri);
    both += clip_and_check(*tri, g.plane((i % 2) ? 'S' : 'E'), neg, pos) == ClipSide::Both;
  }
  EXPECT_GT(both, 300);
}

TEST(GeometryClip, IteratedClippingKeepsInvariants) {
  // Repeated cuts produce vertices of every kind (SEA, SAA, SSE, SSA, ...) and
  // polygons with many sides; closure keeps every value inside its type.
  Gen g(32);
  Polygon neg, pos;
  int splits = 0;
  std::size_t max_size = 0;
  for (int run = 0; run < 150; ++run) {
    const auto t = g.triangle();
    Polygon cur = *make_triangle(t[0], t[1], t[2]);
    for (int step = 0; step < 12; ++step) {
      Plane split;
      if (step % 3 == 2) {
        split = g.plane('S');
      } else {
        // An axis plane through the current polygon's approximate extent.
        const int axis = static_cast<int>(g.uniform(0, 2));
        double lo = 1e300, hi = -1e300;
        for (const Point& v : cur.vertices) lo = std::min(lo, approx(v)[axis]), hi = std::max(hi, approx(v)[axis]);
        split = axis_plane(axis, std::clamp<std::int64_t>(std::llround((lo + hi) / 2), -kCoordLimit, kCoordLimit));
      }
      if (clip_and_check(cur, split, neg, pos) == ClipSide::Both) {
        cur = (step % 2) ? neg : pos;
        ++splits;
        max_size = std::max(max_size, cur.size());
      }
      if (::testing::Test::HasFailure()) return;
    }
  }
  EXPECT_GT(splits, 1000);
  EXPECT_GE(max_size, 6u);
}

TEST(GeometryClip, PlaneThroughOneVertex) {
  const auto tri = make_triangle({0, 0, 0}, {10, 0, 0}, {0, 10, 0});
  Polygon neg, pos;
  const Plane diag{1, -1, 0, 0};  // x = y: through vertex 0, crossing the hypotenuse at (5, 5)
  ASSERT_EQ(clip_and_check(*tri, diag, neg, pos), ClipSide::Both);
  EXPECT_EQ(neg.size(), 3u);
  EXPECT_EQ(pos.size(), 3u);
}

TEST(GeometryClip, PlaneCuttingTwoEdgesGivesQuadAndTriangle) {
  const auto tri = make_triangle({0, 0, 0}, {10, 0, 0}, {0, 10, 0});
  Polygon neg, pos;
  ASSERT_EQ(clip_and_check(*tri, axis_plane(0, 5), neg, pos), ClipSide::Both);
  EXPECT_EQ(neg.size(), 4u);
  EXPECT_EQ(pos.size(), 3u);
  // The new vertices are (5, 0, 0) and (5, 5, 0).
  int found = 0;
  for (const Point& v : pos.vertices) {
    const auto a = approx(v);
    found += (a[0] == 5 && a[1] == 0) + (a[0] == 5 && a[1] == 5);
  }
  EXPECT_EQ(found, 2);
}

TEST(GeometryClip, PlaneThroughTwoVerticesOrTouchingDoesNotSplit) {
  const auto tri = make_triangle({0, 0, 0}, {10, 0, 0}, {0, 10, 0});
  Polygon neg, pos;
  EXPECT_EQ(clip_and_check(*tri, axis_plane(1, 0), neg, pos), ClipSide::Positive);  // contains edge 0
  EXPECT_EQ(clip_and_check(*tri, -axis_plane(1, 0), neg, pos), ClipSide::Negative);
  EXPECT_EQ(clip_and_check(*tri, Plane{0, 1, 1, 0}, neg, pos), ClipSide::Positive);  // tilted about edge 0
  EXPECT_EQ(clip_and_check(*tri, axis_plane(0, 10), neg, pos), ClipSide::Negative);  // touches vertex 1
  EXPECT_EQ(clip_and_check(*tri, axis_plane(0, 11), neg, pos), ClipSide::Negative);
}

TEST(GeometryClip, AllOnPlaneAndUntouchedOutputs) {
  const auto tri = make_triangle({0, 0, 0}, {10, 0, 0}, {0, 10, 0});
  const auto other = make_triangle({1, 1, 1}, {2, 1, 1}, {1, 2, 1});
  Polygon neg = *other, pos = *other;
  EXPECT_EQ(clip(*tri, tri->support, neg, pos), ClipSide::On);
  EXPECT_EQ(clip(*tri, -tri->support, neg, pos), ClipSide::On);
  EXPECT_EQ(clip(*tri, axis_plane(2, 0), neg, pos), ClipSide::On);
  EXPECT_EQ(clip(*tri, axis_plane(2, 1), neg, pos), ClipSide::Negative);
  EXPECT_EQ(clip(*tri, axis_plane(2, -1), neg, pos), ClipSide::Positive);
  for (const Polygon* p : {&neg, &pos}) {
    EXPECT_TRUE(p->support == other->support);
    ASSERT_EQ(p->size(), 3u);
    for (int i = 0; i < 3; ++i) EXPECT_TRUE(p->edges[i] == other->edges[i]);
  }
}

TEST(GeometryClip, PrecomputedSignsGiveTheSameResult) {
  Gen g(33);
  Polygon n1, p1, n2, p2;
  for (int i = 0; i < 500; ++i) {
    const auto t = g.triangle();
    const auto tri = make_triangle(t[0], t[1], t[2]);
    const Plane split = g.plane("SEA"[i % 3]);
    std::vector<std::int8_t> signs;
    for (const Point& v : tri->vertices) signs.push_back(static_cast<std::int8_t>(classify(v, split)));
    const ClipSide a = clip(*tri, split, n1, p1);
    const ClipSide b = clip(*tri, signs, split, n2, p2);
    ASSERT_EQ(a, b);
    EXPECT_EQ(clip_side(signs), a);
    if (a != ClipSide::Both) continue;
    ASSERT_EQ(n1.size(), n2.size());
    ASSERT_EQ(p1.size(), p2.size());
    for (std::size_t k = 0; k < n1.size(); ++k) EXPECT_TRUE(n1.edges[k] == n2.edges[k]);
    for (std::size_t k = 0; k < p1.size(); ++k) EXPECT_TRUE(p1.edges[k] == p2.edges[k]);
  }
}

TEST(GeometryClip, OutputsReuseTheirCapacity) {
  Polygon neg, pos;
  neg.vertices.reserve(16), neg.edges.reserve(16), pos.vertices.reserve(16), pos.edges.reserve(16);
  const Point* nv = neg.vertices.data();
  const Plane* ne = neg.edges.data();
  const Point* pv = pos.vertices.data();
  Gen g(34);
  int both = 0;
  for (int i = 0; i < 1000; ++i) {
    const auto tri = make_triangle({0, 0, 0}, {1000, 0, 0}, {0, 1000, 0});
    both += clip(*tri, axis_plane(static_cast<int>(g.uniform(0, 1)), g.uniform(1, 999)), neg, pos) == ClipSide::Both;
    ASSERT_EQ(neg.vertices.data(), nv);
    ASSERT_EQ(neg.edges.data(), ne);
    ASSERT_EQ(pos.vertices.data(), pv);
  }
  EXPECT_EQ(both, 1000);
}

}  // namespace
}  // namespace ember::test
