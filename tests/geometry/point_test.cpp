// Intersections of three planes and classification of homogeneous points
// against the GMP oracle, for every combination of plane kinds.
#include <gtest/gtest.h>

#include <string>

#include "support/geometry_oracle.hpp"

namespace ember::test {
namespace {

const char* const kTriples[] = {"SSS", "SSE", "SEE", "EEE", "SSA", "SEA", "EEA", "SAA", "EAA", "AAA"};

TEST(GeometryPoint, IntersectMatchesOracleForEveryKindTriple) {
  Gen g(10);
  int max_xyz = 0, max_w = 0, max_cls = 0;
  for (const char* kinds : kTriples) {
    int made = 0;
    for (int i = 0; i < 1500; ++i) {
      Plane pl[3] = {g.plane(kinds[0]), g.plane(kinds[1]), g.plane(kinds[2])};
      // Vary the order so every kind appears in every row of the minors.
      std::rotate(pl, pl + (i % 3), pl + 3);
      const MpPoint o = oracle_intersect(to_mp(pl[0]), to_mp(pl[1]), to_mp(pl[2]));
      const auto x = intersect(pl[0], pl[1], pl[2]);
      if (o[3] == 0) {
        EXPECT_FALSE(x.has_value()) << kinds;
        continue;
      }
      ASSERT_TRUE(x.has_value()) << kinds;
      ++made;
      EXPECT_EQ(to_mp(*x), o) << kinds;
      for (const Plane& p : pl) {
        EXPECT_EQ(classify(*x, p), 0) << kinds;
        EXPECT_EQ(classify(*x, -p), 0) << kinds;
      }
      for (int k = 0; k < 3; ++k) max_xyz = std::max(max_xyz, bits_of(o[k]));
      max_w = std::max(max_w, bits_of(o[3]));
      // Classify against a plane of every kind.
      for (char c : std::string("SEA")) {
        const Plane s = g.plane(c);
        const mpz_class v = dot(to_mp(s), o);
        EXPECT_EQ(classify(*x, s), sign_of(v)) << kinds << " vs " << c;
        EXPECT_EQ(to_mpz(classify_value(*x, s)), v);
        max_cls = std::max(max_cls, bits_of(v));
      }
    }
    EXPECT_GT(made, 300) << kinds;  // A and E planes are often dependent (shared axes)
  }
  EXPECT_LE(max_w, PointW::bits);
  EXPECT_LE(max_xyz, PointXYZ::bits);
  EXPECT_LE(max_cls, ClassifyValue::bits);
  // Sanity: random SSS data really exercises wide values (numerics.md: 162/189/244).
  EXPECT_GE(max_w, 150);
  EXPECT_GE(max_xyz, 175);
}

TEST(GeometryPoint, FilteredClassifyMatchesOracleNearPlanes) {
  // Planes through a computed point, then shifted by the smallest possible
  // offset (d +- 1) or rotated slightly: the double estimate is useless there,
  // so the filter must defer to the exact predicate every time it is unsure.
  Gen g(77);
  int decided = 0;
  for (const char* kinds : kTriples) {
    for (int i = 0; i < 300; ++i) {
      const Plane pl[3] = {g.plane(kinds[0]), g.plane(kinds[1]), g.plane(kinds[2])};
      const auto x = intersect(pl[0], pl[1], pl[2]);
      if (!x) continue;
      for (const Plane& base : pl) {
        for (int delta : {-1, 1}) {
          Plane s = base;
          s.d = OffsetCoef::assume_bound(s.d + OffsetCoef(delta));
          const int expected = sign_of(dot(to_mp(s), to_mp(*x)));
          EXPECT_EQ(classify(*x, s), expected) << kinds;
          EXPECT_EQ(classify_exact(*x, s), expected) << kinds;
          ++decided;
        }
      }
    }
  }
  EXPECT_GT(decided, 5000);
}

TEST(GeometryPoint, IntersectIsNulloptForDependentNormals) {
  Gen g(11);
  for (int i = 0; i < 500; ++i) {
    const Plane p = g.plane("SEA"[i % 3]);
    const Plane r = g.plane('S');
    // Two parallel planes.
    Plane q = p;
    q.d = OffsetCoef::assume_bound(q.d - OffsetCoef(3));
    EXPECT_FALSE(intersect(p, q, r));
    EXPECT_FALSE(intersect(r, -p, p));
  }
  // Three planes through one line (the z axis).
  EXPECT_FALSE(intersect(axis_plane(0, 0), axis_plane(1, 0), Plane{1, 1, 0, 0}));
  // Three parallel-to-z planes that do not share a line.
  EXPECT_FALSE(intersect(axis_plane(0, 1), axis_plane(1, 0), Plane{1, 1, 0, 0}));
}

TEST(GeometryPoint, AxisTripleGivesTheGridPoint) {
  const auto x = intersect(axis_plane(2, 5), -axis_plane(0, -3), axis_plane(1, kCoordLimit));
  ASSERT_TRUE(x);
  EXPECT_FALSE(x->w.negative());
  const auto c = approx(*x);
  EXPECT_EQ(c[0], -3.0);
  EXPECT_EQ(c[1], static_cast<double>(kCoordLimit));
  EXPECT_EQ(c[2], 5.0);
  EXPECT_EQ(classify(*x, axis_plane(0, -3)), 0);
  EXPECT_EQ(classify(*x, axis_plane(0, -4)), 1);
}

TEST(GeometryPoint, ToPointAgreesWithIntegerClassify) {
  Gen g(12);
  for (int i = 0; i < 20000; ++i) {
    const IntPoint p = g.point();
    const Plane s = g.plane("SEA"[i % 3]);
    EXPECT_EQ(classify(to_point(p), s), classify(p, s));
  }
}

TEST(GeometryPoint, StoredGridPointsClassifyExactlyOnAndNearPlanes) {
  // classify_exact of a point stored with w = 1 takes the 82-bit integer
  // classify: against GMP, for corners of the planes' own triangles (exact
  // zeros, at the cube's corners too), their neighbours one grid step away,
  // and random points; the general 243-bit value must agree as well. Points
  // with w = 1 outside the grid's range and a grid point stored with w = 2
  // are no stored grid points and take the general path.
  Gen g(14);
  int zeros = 0;
  for (int i = 0; i < 20000; ++i) {
    const auto t = g.triangle();
    const Plane s = *supporting_plane(t[0], t[1], t[2]);
    const int k = static_cast<int>(g.rng()() % 3);
    for (const IntPoint& p : {t[k], IntPoint{t[k].x, t[k].y, t[k].z + (t[k].z > 0 ? -1 : 1)}, g.point()}) {
      const Point pt = to_point(p);
      ASSERT_TRUE(stored_grid_point(pt));
      const int expected = sign_of(dot(to_mp(s), to_mp(p)));
      zeros += expected == 0;
      ASSERT_EQ(classify_exact(pt, s), expected);
      ASSERT_EQ(classify_value(pt, s).sign(), expected);
      ASSERT_EQ(classify(pt, s), expected);
    }
  }
  EXPECT_GT(zeros, 19000);
  const Plane s{1, 1, 1, 0};
  const Point far{PointXYZ(std::int64_t{1} << 40), PointXYZ(-(std::int64_t{1} << 40)), PointXYZ(1), PointW(1), {}};
  EXPECT_FALSE(stored_grid_point(far));
  EXPECT_EQ(classify_exact(far, s), 1);
  const Point scaled{PointXYZ(6), PointXYZ(-4), PointXYZ(-2), PointW(2), {}};  // (3, -2, -1), w = 2
  EXPECT_FALSE(stored_grid_point(scaled));
  EXPECT_EQ(classify_exact(scaled, s), 0);
}

TEST(GeometryPoint, ClassifyAxisAgreesWithGeneralClassify) {
  Gen g(13);
  int zeros = 0;
  for (int i = 0; i < 3000; ++i) {
    const char* kinds = kTriples[i % 10];
    const auto x = intersect(g.plane(kinds[0]), g.plane(kinds[1]), g.plane(kinds[2]));
    if (!x) continue;
    for (int axis = 0; axis < 3; ++axis) {
      // Positions near the point (rounded Cartesian coordinate) and random ones.
      const double c = approx(*x)[axis];
      const std::int64_t near =
          std::clamp<std::int64_t>(static_cast<std::int64_t>(std::llround(c)), -kCoordLimit, kCoordLimit);
      for (const std::int64_t pos : {near, g.coord()}) {
        const int s = classify_axis(*x, axis, pos);
        EXPECT_EQ(s, classify(*x, axis_plane(axis, pos)));
        zeros += s == 0;
      }
    }
  }
  EXPECT_GT(zeros, 100);  // points with an A plane sit exactly on it
}

TEST(GeometryPoint, AxisSpecializedIntersectionEqualsGeneral) {
  // clip() builds new vertices with detail::intersect_raw_axis; it must give the
  // very same homogeneous vector as the general Cramer expansion.
  Gen g(15);
  int nonzero = 0;
  for (int i = 0; i < 6000; ++i) {
    const Plane p = g.plane("SEA"[i % 3]), q = g.plane("SE"[(i / 3) % 2]);
    const int axis = static_cast<int>(g.uniform(0, 2));
    const std::int64_t t = g.coord();
    Point a, b;
    const bool ok_a = detail::intersect_raw_axis(p, q, axis, t, a);
    const bool ok_b = detail::intersect_raw(p, q, axis_plane(axis, t), b);
    ASSERT_EQ(ok_a, ok_b);
    EXPECT_EQ(to_mp(a), to_mp(b));
    nonzero += ok_a;
  }
  EXPECT_GT(nonzero, 3000);
}

TEST(GeometryPoint, ApproxIsCloseToExactRational) {
  Gen g(14);
  for (int i = 0; i < 2000; ++i) {
    const char* kinds = kTriples[i % 10];
    Plane pl[3] = {g.plane(kinds[0]), g.plane(kinds[1]), g.plane(kinds[2])};
    const auto x = intersect(pl[0], pl[1], pl[2]);
    if (!x) continue;
    const MpPoint o = to_mp(*x);
    const auto a = approx(*x);
    for (int k = 0; k < 3; ++k) {
      const mpq_class exact(o[k], o[3]);
      const double e = mpq_class(exact).get_d();
      EXPECT_LE(std::abs(a[k] - e), 1e-12 * std::max(1.0, std::abs(e))) << kinds;
    }
  }
}

}  // namespace
}  // namespace ember::test
