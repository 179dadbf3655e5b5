// Polygon construction and point location.
#include <gtest/gtest.h>

#include "support/polygon_check.hpp"

namespace ember::test {
namespace {

TEST(GeometryPolygon, RandomTrianglesSatisfyConventions) {
  Gen g(20);
  for (int i = 0; i < 3000; ++i) {
    const auto t =
        (i % 2) ? g.triangle() : std::array<IntPoint, 3>{g.small_point(8), g.small_point(8), g.small_point(8)};
    const auto poly = make_triangle(t[0], t[1], t[2]);
    if (!supporting_plane(t[0], t[1], t[2])) {
      EXPECT_FALSE(poly);
      continue;
    }
    ASSERT_TRUE(poly);
    ASSERT_TRUE(check_polygon(*poly)) << "triangle " << i;
    // Vertex i is support ∩ edges[i-1] ∩ edges[i]: the computed intersection
    // is the same point (incident to the grid point's three axis planes).
    for (int v = 0; v < 3; ++v) {
      const auto x = intersect(poly->support, poly->edges[(v + 2) % 3], poly->edges[v]);
      ASSERT_TRUE(x);
      EXPECT_EQ(classify(*x, axis_plane(0, t[v].x)), 0);
      EXPECT_EQ(classify(*x, axis_plane(1, t[v].y)), 0);
      EXPECT_EQ(classify(*x, axis_plane(2, t[v].z)), 0);
    }
    EXPECT_NE(projected_area2(*poly), 0);
  }
}

TEST(GeometryPolygon, DegenerateTrianglesRejected) {
  EXPECT_FALSE(make_triangle({0, 0, 0}, {1, 1, 1}, {2, 2, 2}));
  EXPECT_FALSE(make_triangle({5, 5, 5}, {5, 5, 5}, {1, 2, 3}));
  EXPECT_FALSE(make_triangle({-kCoordLimit, 0, kCoordLimit}, {0, 0, 0}, {kCoordLimit, 0, -kCoordLimit}));
  EXPECT_THROW(make_triangle({0, 0, 0}, {1, 0, 0}, {0, kCoordLimit + 1, 0}), Error);
}

TEST(GeometryPolygon, ConvexPolygonsAccepted) {
  // A tilted octagon in the plane x + 2y - z = 0 (z = x + 2y), CCW around (1, 2, -1).
  const std::int64_t xy[8][2] = {{3, 0}, {2, 2}, {0, 3}, {-2, 2}, {-3, 0}, {-2, -2}, {0, -3}, {2, -2}};
  std::vector<IntPoint> pts;
  for (auto [x, y] : xy) pts.push_back({x * 1000, y * 1000, x * 1000 + 2 * y * 1000});
  const auto poly = make_convex_polygon(pts);
  ASSERT_TRUE(poly);
  EXPECT_TRUE(check_polygon(*poly));
  EXPECT_EQ(poly->size(), 8u);
  // The reversed order is accepted with the flipped support.
  std::vector<IntPoint> rev(pts.rbegin(), pts.rend());
  const auto r = make_convex_polygon(rev);
  ASSERT_TRUE(r);
  EXPECT_TRUE(check_polygon(*r));
  EXPECT_TRUE(coplanar(r->support, poly->support));
  EXPECT_FALSE(same_orientation(r->support, poly->support));
  // A full-range square.
  const std::int64_t L = kCoordLimit;
  const IntPoint sq[4] = {{-L, -L, L}, {L, -L, -L}, {L, L, -L}, {-L, L, L}};
  const auto s = make_convex_polygon(sq);
  ASSERT_TRUE(s);
  EXPECT_TRUE(check_polygon(*s));
}

TEST(GeometryPolygon, NonConvexOrNonPlanarRejected) {
  const IntPoint quad[4] = {{0, 0, 0}, {10, 0, 0}, {10, 10, 0}, {0, 10, 0}};
  const IntPoint nonplanar[4] = {{0, 0, 0}, {10, 0, 0}, {10, 10, 1}, {0, 10, 0}};
  const IntPoint reflex[5] = {{0, 0, 0}, {10, 0, 0}, {10, 10, 0}, {5, 3, 0}, {0, 10, 0}};
  const IntPoint collinear[4] = {{0, 0, 0}, {5, 0, 0}, {10, 0, 0}, {0, 10, 0}};
  const IntPoint repeated[4] = {{0, 0, 0}, {10, 0, 0}, {10, 0, 0}, {0, 10, 0}};
  // Pentagram: every turn is left, but it winds twice.
  const IntPoint star[5] = {{0, 100, 0}, {-59, -81, 0}, {95, 31, 0}, {-95, 31, 0}, {59, -81, 0}};
  EXPECT_TRUE(make_convex_polygon(quad));
  EXPECT_FALSE(make_convex_polygon(nonplanar));
  EXPECT_FALSE(make_convex_polygon(reflex));
  EXPECT_FALSE(make_convex_polygon(collinear));
  EXPECT_FALSE(make_convex_polygon(repeated));
  EXPECT_FALSE(make_convex_polygon(star));
  EXPECT_FALSE(make_convex_polygon(std::span<const IntPoint>(quad, 2)));
}

TEST(GeometryPolygon, LocateInsideBoundaryOutside) {
  const auto tri = make_triangle({0, 0, 0}, {12, 0, 0}, {0, 12, 0});
  ASSERT_TRUE(tri);
  auto at = [](std::int64_t x, std::int64_t y) { return to_point(IntPoint{x, y, 0}); };
  EXPECT_EQ(locate(*tri, at(1, 1)), -1);
  EXPECT_EQ(locate(*tri, at(6, 6)), 0);  // hypotenuse
  EXPECT_EQ(locate(*tri, at(0, 0)), 0);  // vertex
  EXPECT_EQ(locate(*tri, at(4, 0)), 0);  // edge
  EXPECT_EQ(locate(*tri, at(7, 6)), 1);
  EXPECT_EQ(locate(*tri, at(-1, 3)), 1);
  // A rational point: (1/3, 1/3) via three planes 3x = 1, 3y = 1, z = 0.
  const auto q = intersect(Plane{3, 0, 0, -1}, Plane{0, 3, 0, -1}, tri->support);
  ASSERT_TRUE(q);
  EXPECT_EQ(locate(*tri, *q), -1);
  // (6.5, 5.5) lies exactly on the hypotenuse x + y = 12.
  const auto h = intersect(Plane{2, 0, 0, -13}, Plane{0, 2, 0, -11}, tri->support);
  ASSERT_TRUE(h);
  EXPECT_EQ(locate(*tri, *h), 0);
}

}  // namespace
}  // namespace ember::test
