// Line and segment versus polygon, including exact degenerate hits.
#include <gtest/gtest.h>

#include "support/polygon_check.hpp"

namespace ember::test {
namespace {

class GeometryIntersect : public ::testing::Test {
 protected:
  // Triangle in z = 0 with normal +z.
  Polygon tri = *make_triangle({0, 0, 0}, {12, 0, 0}, {0, 12, 0});
  static Plane X(std::int64_t v) { return axis_plane(0, v); }
  static Plane Y(std::int64_t v) { return axis_plane(1, v); }
  static Plane Z(std::int64_t v) { return axis_plane(2, v); }
};

TEST_F(GeometryIntersect, LineKinds) {
  Point hit;
  EXPECT_EQ(intersect_line(X(2), Y(3), tri, &hit), LineHit::Interior);
  EXPECT_EQ(approx(hit)[0], 2.0);
  EXPECT_EQ(approx(hit)[1], 3.0);
  EXPECT_EQ(approx(hit)[2], 0.0);
  EXPECT_EQ(classify(hit, tri.support), 0);
  EXPECT_EQ(intersect_line(X(6), Y(6), tri, &hit), LineHit::Boundary);  // hypotenuse
  EXPECT_EQ(intersect_line(X(0), Y(0), tri, &hit), LineHit::Boundary);  // vertex
  EXPECT_EQ(intersect_line(X(5), -Y(0), tri, nullptr), LineHit::Boundary);
  EXPECT_EQ(intersect_line(X(7), Y(6), tri, nullptr), LineHit::Miss);
  // A slanted line (x = z + 1, y = z + 1) through (1, 1, 0).
  EXPECT_EQ(intersect_line(Plane{1, 0, -1, -1}, Plane{0, 1, -1, -1}, tri, nullptr), LineHit::Interior);
}

TEST_F(GeometryIntersect, LineInOrParallelToSupport) {
  Point hit = to_point({99, 99, 99});
  EXPECT_EQ(intersect_line(Z(0), X(2), tri, &hit), LineHit::InPlane);
  EXPECT_EQ(intersect_line(Z(0), X(50), tri, &hit), LineHit::InPlane);  // no overlap, still InPlane
  EXPECT_EQ(intersect_line(Plane{1, 0, 1, 0}, Plane{1, 0, -1, 0}, tri, &hit),
            LineHit::InPlane);                                      // x = z = 0, as a pencil
  EXPECT_EQ(intersect_line(Z(1), X(2), tri, &hit), LineHit::Miss);  // parallel, above
  EXPECT_EQ(approx(hit)[0], 99.0);                                  // untouched
}

TEST_F(GeometryIntersect, SegmentBoundsAndEndpoints) {
  Point hit;
  // Segment along the z line x = 2, y = 3 between z = -1 and z = 5: r0 = (z <= 5), r1 = (z >= -1).
  SegmentHit h = intersect_segment(X(2), Y(3), Z(5), -Z(-1), tri, &hit);
  EXPECT_EQ(h.kind, LineHit::Interior);
  EXPECT_FALSE(h.at_endpoint);
  h = intersect_segment(X(2), Y(3), Z(0), -Z(-1), tri, &hit);  // ends on the triangle
  EXPECT_EQ(h.kind, LineHit::Interior);
  EXPECT_TRUE(h.at_endpoint);
  h = intersect_segment(X(2), Y(3), -Z(1), Z(5), tri, &hit);  // z in [1, 5]: misses
  EXPECT_EQ(h.kind, LineHit::Miss);
  EXPECT_FALSE(h.at_endpoint);
  h = intersect_segment(X(0), Y(4), Z(0), -Z(-3), tri, &hit);  // on an edge and at an endpoint
  EXPECT_EQ(h.kind, LineHit::Boundary);
  EXPECT_TRUE(h.at_endpoint);
  h = intersect_segment(X(20), Y(4), Z(0), -Z(-3), tri, &hit);  // endpoint outside the triangle
  EXPECT_EQ(h.kind, LineHit::Miss);
  h = intersect_segment(Z(0), Y(4), X(3), -X(-3), tri, &hit);
  EXPECT_EQ(h.kind, LineHit::InPlane);
}

TEST_F(GeometryIntersect, RandomLinesAgreeWithOracle) {
  Gen g(40);
  int counts[4] = {};
  for (int i = 0; i < 6000; ++i) {
    const auto t =
        (i % 2) ? g.triangle() : std::array<IntPoint, 3>{g.small_point(9), g.small_point(9), g.small_point(9)};
    const auto poly = make_triangle(t[0], t[1], t[2]);
    if (!poly) continue;
    // Lines of kinds AA (through a grid point near the triangle), SA, SE, EA,
    // and lines built from the triangle's own edge planes (exact boundary hits).
    Plane l0, l1;
    switch (i % 5) {
      case 0: {
        const IntPoint c = t[g.uniform(0, 2)];
        const int ax = static_cast<int>(g.uniform(0, 2));
        l0 = axis_plane((ax + 1) % 3, (&c.x)[(ax + 1) % 3]);
        l1 = axis_plane((ax + 2) % 3,
                        std::clamp<std::int64_t>((&c.x)[(ax + 2) % 3] + g.uniform(-3, 3), -kCoordLimit, kCoordLimit));
        break;
      }
      case 1: l0 = g.plane('S'), l1 = g.plane('A'); break;
      case 2: l0 = g.plane('S'), l1 = g.plane('E'); break;
      case 3: l0 = poly->edges[g.uniform(0, 2)], l1 = g.plane('A'); break;
      default: l0 = poly->support, l1 = g.plane('A'); break;  // in plane (or parallel)
    }
    if (parallel(l0, l1)) continue;
    const MpPoint o = oracle_intersect(to_mp(l0), to_mp(l1), to_mp(poly->support));
    LineHit expect;
    if (o[3] == 0) {
      expect = (o[0] == 0 && o[1] == 0 && o[2] == 0) ? LineHit::InPlane : LineHit::Miss;
    } else {
      int worst = -1;
      for (const Plane& e : poly->edges) worst = std::max(worst, sign_of(dot(to_mp(e), o)));
      expect = worst > 0 ? LineHit::Miss : (worst == 0 ? LineHit::Boundary : LineHit::Interior);
    }
    Point hit;
    const LineHit got = intersect_line(l0, l1, *poly, &hit);
    ASSERT_EQ(got, expect) << "case " << i;
    if (got == LineHit::Interior || got == LineHit::Boundary) {
      EXPECT_EQ(to_mp(hit), o);
    }
    counts[static_cast<int>(got)]++;
  }
  for (int k = 0; k < 4; ++k) EXPECT_GT(counts[k], 50) << "kind " << k;
}

TEST_F(GeometryIntersect, RandomSegmentsAgreeWithOracle) {
  Gen g(41);
  int endpoints = 0, hits = 0;
  for (int i = 0; i < 4000; ++i) {
    // Small triangles and integer lines: hits often land on grid points, edges
    // and segment ends, exercising the exact zero cases.
    const auto t = std::array<IntPoint, 3>{g.small_point(3), g.small_point(3), g.small_point(3)};
    const auto poly = make_triangle(t[0], t[1], t[2]);
    if (!poly) continue;
    const int ax = static_cast<int>(g.uniform(0, 2));
    const Plane l0 = axis_plane((ax + 1) % 3, g.uniform(-3, 3)), l1 = axis_plane((ax + 2) % 3, g.uniform(-3, 3));
    const std::int64_t lo = g.uniform(-4, 4), hi = g.uniform(lo, 4);
    const Plane r0 = axis_plane(ax, hi), r1 = -axis_plane(ax, lo);  // lo <= x_ax <= hi
    const MpPoint o = oracle_intersect(to_mp(l0), to_mp(l1), to_mp(poly->support));
    Point hit;
    const SegmentHit got = intersect_segment(l0, l1, r0, r1, *poly, &hit);
    if (o[3] == 0) {
      EXPECT_NE(got.kind, LineHit::Interior);
      EXPECT_NE(got.kind, LineHit::Boundary);
      continue;
    }
    const int c0 = sign_of(dot(to_mp(r0), o)), c1 = sign_of(dot(to_mp(r1), o));
    int worst = -1;
    for (const Plane& e : poly->edges) worst = std::max(worst, sign_of(dot(to_mp(e), o)));
    const LineHit expect = (c0 > 0 || c1 > 0 || worst > 0) ? LineHit::Miss
                           : worst == 0                    ? LineHit::Boundary
                                                           : LineHit::Interior;
    ASSERT_EQ(got.kind, expect) << "case " << i;
    EXPECT_EQ(got.at_endpoint, expect != LineHit::Miss && (c0 == 0 || c1 == 0));
    endpoints += got.at_endpoint;
    hits += expect != LineHit::Miss;
  }
  EXPECT_GT(hits, 100);
  EXPECT_GT(endpoints, 20);
}

}  // namespace
}  // namespace ember::test
