#pragma once
// Shared invariant checks for polygons: exact incidence of every vertex with its
// defining planes, strict convexity, and the exact (rational) projected area.
#include <gtest/gtest.h>

#include "support/geometry_oracle.hpp"

namespace ember::test {

/// Checks the conventions of polygon.hpp exactly; returns false (with gtest
/// failures) on the first violation.
inline bool check_polygon(const Polygon& poly) {
  const std::size_t n = poly.size();
  EXPECT_GE(n, 3u);
  EXPECT_EQ(poly.edges.size(), n);
  if (n < 3 || poly.edges.size() != n) return false;
  for (std::size_t i = 0; i < n; ++i) {
    const Point& v = poly.vertices[i];
    EXPECT_TRUE(v.w > PointW(0)) << "vertex " << i;
    EXPECT_EQ(classify(v, poly.support), 0) << "vertex " << i << " off the support";
    const std::size_t prev = (i + n - 1) % n;
    for (std::size_t e = 0; e < n; ++e) {
      const int s = classify(v, poly.edges[e]);
      if (e == i || e == prev) {
        EXPECT_EQ(s, 0) << "vertex " << i << " not on its edge plane " << e;
        if (s != 0) return false;
      } else {
        EXPECT_EQ(s, -1) << "vertex " << i << " not strictly inside edge plane " << e;
        if (s != -1) return false;
      }
    }
  }
  return !::testing::Test::HasFailure();
}

/// Twice the signed area of the polygon projected along the dominant axis of its
/// support (exact rational from the homogeneous vertices).
inline mpq_class projected_area2(const Polygon& poly) {
  const int k = dominant_axis(poly.support);
  const int u = (k + 1) % 3, v = (k + 2) % 3;
  std::vector<std::array<mpq_class, 2>> pts;
  for (const Point& p : poly.vertices) {
    const MpPoint o = to_mp(p);
    pts.push_back({mpq_class(o[u], o[3]), mpq_class(o[v], o[3])});
    pts.back()[0].canonicalize();
    pts.back()[1].canonicalize();
  }
  mpq_class a = 0;
  for (std::size_t i = 0; i < pts.size(); ++i) {
    const auto& p = pts[i];
    const auto& q = pts[(i + 1) % pts.size()];
    a += p[0] * q[1] - q[0] * p[1];
  }
  return a;
}

}  // namespace ember::test
