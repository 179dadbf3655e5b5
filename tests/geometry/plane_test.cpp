// Plane construction and plane-pair predicates against the GMP oracle.
#include <gtest/gtest.h>

#include "support/geometry_oracle.hpp"

namespace ember::test {
namespace {

constexpr std::int64_t L = kCoordLimit;

TEST(GeometryPlane, SupportingPlaneMatchesOracleWithinBounds) {
  Gen g(1);
  int max_n = 0, max_d = 0;
  // Corner triangles first: they produce the largest normals and offsets.
  std::vector<std::array<IntPoint, 3>> tris = {
      {IntPoint{-L, -L, -L}, IntPoint{L, -L, L}, IntPoint{-L, L, L}},
      {IntPoint{L, L, L}, IntPoint{-L, L, -L}, IntPoint{L, -L, -L}},
      {IntPoint{-L, -L, L}, IntPoint{L, -L, -L}, IntPoint{L, L, L}},
  };
  for (int i = 0; i < 20000; ++i) tris.push_back({g.point(), g.point(), g.point()});
  int built = 0;
  for (const auto& t : tris) {
    const auto p = supporting_plane(t[0], t[1], t[2]);
    const MpPlane o = oracle_support(t[0], t[1], t[2]);
    if (o[0] == 0 && o[1] == 0 && o[2] == 0) {
      EXPECT_FALSE(p.has_value());
      continue;
    }
    ASSERT_TRUE(p.has_value());
    ++built;
    EXPECT_EQ(to_mp(*p), o);
    for (int k = 0; k < 3; ++k) max_n = std::max(max_n, bits_of(o[k]));
    max_d = std::max(max_d, bits_of(o[3]));
    for (const IntPoint& v : t) EXPECT_EQ(classify(v, *p), 0);
  }
  EXPECT_GT(built, 19000);
  EXPECT_LE(max_n, 53);  // |n_k| <= 2^52 has at most 53 bits
  EXPECT_LE(max_d, NormalCoef::bits + 26);
  EXPECT_LE(max_d, OffsetCoef::bits);
  EXPECT_GE(max_n, 52);  // the corner triangles reach the bound
}

TEST(GeometryPlane, GridNormalMatchesOracleAtFullRange) {
  Gen g(7);
  std::vector<std::array<IntPoint, 3>> tris = {
      {IntPoint{-L, -L, -L}, IntPoint{L, -L, L}, IntPoint{-L, L, L}},  // components reach 2^52
      {IntPoint{L, L, L}, IntPoint{-L, L, -L}, IntPoint{L, -L, -L}},
      {IntPoint{-L, 0, L}, IntPoint{0, 0, 0}, IntPoint{L, 0, -L}},  // collinear
  };
  for (int i = 0; i < 20000; ++i) tris.push_back({g.point(), g.point(), g.point()});
  int max_bits = 0, zero = 0;
  for (const auto& t : tris) {
    const std::array<std::int64_t, 3> n = grid_normal(t[0], t[1], t[2]);
    const MpPlane o = oracle_support(t[0], t[1], t[2]);
    for (int k = 0; k < 3; ++k) {
      ASSERT_EQ(mpz64(n[k]), o[k]);
      max_bits = std::max(max_bits, bits_of(o[k]));
    }
    zero += n == std::array<std::int64_t, 3>{0, 0, 0};
  }
  EXPECT_GE(max_bits, 52);  // the corner triangles exercise the bound
  EXPECT_GE(zero, 1);
}

TEST(GeometryPlane, GridOrient3dMatchesOracleAtFullRange) {
  // Random quadruples at the corners of the range and uniform, plus
  // coplanar ones (d on the plane of a, b, c by construction: zero).
  Gen g(11);
  int max_bits = 0, zeros = 0;
  for (int i = 0; i < 40000; ++i) {
    const IntPoint a = g.point(), b = g.point(), c = g.point();
    IntPoint d = g.point();
    if (i % 8 == 0) d = IntPoint{a.x + (b.x - a.x) / 2, a.y + (b.y - a.y) / 2, a.z + (b.z - a.z) / 2};  // on line ab
    const MpPlane o = oracle_support(a, b, c);
    const mpz_class want = dot(o, to_mp(d));
    const __int128 got = grid_orient3d(a, b, c, d);
    ASSERT_EQ(mpz_class(static_cast<long>(got >> 64)) * mpz_class("18446744073709551616") +
                  mpz_class(static_cast<unsigned long>(static_cast<std::uint64_t>(got))),
              want);
    max_bits = std::max(max_bits, bits_of(want));
    zeros += want == 0;
  }
  EXPECT_GE(max_bits, 78);  // the corner quadruples reach the bound's order
  EXPECT_GE(zeros, 1000);
}

TEST(GeometryPlane, SupportingPlaneNormalIsCounterClockwise) {
  const auto p = supporting_plane({0, 0, 0}, {1, 0, 0}, {0, 1, 0});
  ASSERT_TRUE(p);
  EXPECT_EQ(p->a, NormalCoef(0));
  EXPECT_EQ(p->b, NormalCoef(0));
  EXPECT_EQ(p->c, NormalCoef(1));
  EXPECT_EQ(classify(IntPoint{0, 0, 5}, *p), 1);
  EXPECT_EQ(classify(IntPoint{0, 0, -5}, *p), -1);
  // Outward normals of a CCW-oriented tetrahedron.
  const IntPoint v[4] = {{0, 0, 0}, {10, 0, 0}, {0, 10, 0}, {0, 0, 10}};
  const int faces[4][3] = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};
  for (int f = 0; f < 4; ++f) {
    const auto s = supporting_plane(v[faces[f][0]], v[faces[f][1]], v[faces[f][2]]);
    ASSERT_TRUE(s);
    EXPECT_EQ(classify(IntPoint{1, 1, 1}, *s), -1) << "face " << f;
  }
}

TEST(GeometryPlane, DegenerateTrianglesRejected) {
  EXPECT_FALSE(supporting_plane({1, 2, 3}, {1, 2, 3}, {4, 5, 6}));
  EXPECT_FALSE(supporting_plane({1, 2, 3}, {4, 5, 6}, {4, 5, 6}));
  EXPECT_FALSE(supporting_plane({-L, -L, -L}, {0, 0, 0}, {L, L, L}));
  EXPECT_FALSE(supporting_plane({-L, L, 0}, {L - 2, -L + 2, 0}, {L, -L, 0}));
  EXPECT_FALSE(supporting_plane({7, 7, 7}, {7, 7, 7}, {7, 7, 7}));
  // Almost collinear at full range is not degenerate.
  EXPECT_TRUE(supporting_plane({-L, -L, -L}, {L, L, L}, {L, L, L - 1}));
}

TEST(GeometryPlane, OutOfRangeCoordinatesThrow) {
  EXPECT_THROW(supporting_plane({L + 1, 0, 0}, {0, 1, 0}, {0, 0, 1}), Error);
  EXPECT_THROW(axis_plane(0, -L - 1), Error);
  EXPECT_THROW(axis_plane(3, 0), Error);
  EXPECT_NO_THROW(supporting_plane({L, -L, L}, {-L, 1, 0}, {0, 0, -L}));
}

TEST(GeometryPlane, EdgePlanesHaveInteriorOnNegativeSide) {
  Gen g(2);
  int seen[3][2] = {};
  for (int i = 0; i < 20000; ++i) {
    const auto t =
        (i % 2) ? g.triangle() : std::array<IntPoint, 3>{g.small_point(20), g.small_point(20), g.small_point(20)};
    const auto s = supporting_plane(t[0], t[1], t[2]);
    if (!s) continue;
    const int k = dominant_axis(*s);
    seen[k][s->normal(k).negative() ? 1 : 0]++;
    for (int e = 0; e < 3; ++e) {
      const Plane ep = edge_plane(t[e], t[(e + 1) % 3], *s);
      EXPECT_EQ(classify(t[e], ep), 0);
      EXPECT_EQ(classify(t[(e + 1) % 3], ep), 0);
      ASSERT_EQ(classify(t[(e + 2) % 3], ep), -1) << "triangle " << i << " edge " << e;
      // Parallel to e_k: the normal has no k component.
      EXPECT_TRUE(ep.normal(k).is_zero());
    }
  }
  for (int k = 0; k < 3; ++k)
    for (int sg = 0; sg < 2; ++sg) EXPECT_GT(seen[k][sg], 100) << "axis " << k << " sign " << sg;
}

TEST(GeometryPlane, EdgePlaneMatchesOracleWithinBounds) {
  Gen g(3);
  int max_m = 0, max_d = 0;
  for (int i = 0; i < 20000; ++i) {
    const auto t = g.triangle();
    const auto s = supporting_plane(t[0], t[1], t[2]);
    const MpPlane so = to_mp(*s);
    int k = 0;  // dominant axis via the oracle
    for (int j = 1; j < 3; ++j)
      if (abs(so[j]) > abs(so[k])) k = j;
    const mpz_class sigma = so[k] < 0 ? -1 : 1;
    const Plane ep = edge_plane(t[0], t[1], *s);
    const mpz_class e[3] = {mpz64(t[1].x) - t[0].x, mpz64(t[1].y) - t[0].y, mpz64(t[1].z) - t[0].z};
    mpz_class ek[3] = {0, 0, 0};
    ek[k] = 1;
    MpPlane o{sigma * (e[1] * ek[2] - e[2] * ek[1]), sigma * (e[2] * ek[0] - e[0] * ek[2]),
              sigma * (e[0] * ek[1] - e[1] * ek[0]), 0};
    o[3] = -(o[0] * t[0].x + o[1] * t[0].y + o[2] * t[0].z);
    EXPECT_EQ(to_mp(ep), o);
    for (int j = 0; j < 3; ++j) max_m = std::max(max_m, bits_of(o[j]));
    max_d = std::max(max_d, bits_of(o[3]));
  }
  EXPECT_LE(max_m, 27);  // |m| <= 2^26
  EXPECT_LE(max_d, 53);  // |d| <= 2^52
}

TEST(GeometryPlane, DominantAxisTiesGoToLowestIndex) {
  EXPECT_EQ(dominant_axis(Plane{1, 1, 1, 0}), 0);
  EXPECT_EQ(dominant_axis(Plane{-1, 2, -2, 0}), 1);
  EXPECT_EQ(dominant_axis(Plane{3, 2, -3, 0}), 0);
  EXPECT_EQ(dominant_axis(Plane{0, 0, -1, 0}), 2);
  EXPECT_EQ(dominant_axis(Plane{0, -5, 4, 0}), 1);
}

TEST(GeometryPlane, AxisPlaneOrientationAndFlip) {
  for (int axis = 0; axis < 3; ++axis) {
    const Plane p = axis_plane(axis, -7);
    IntPoint below{0, 0, 0}, on{0, 0, 0}, above{0, 0, 0};
    (&below.x)[axis] = -8;
    (&on.x)[axis] = -7;
    (&above.x)[axis] = L;
    EXPECT_EQ(classify(below, p), -1);
    EXPECT_EQ(classify(on, p), 0);
    EXPECT_EQ(classify(above, p), 1);
    EXPECT_EQ(classify(above, -p), -1);
    EXPECT_EQ(-(-p), p);
    EXPECT_FALSE(-p == p);
  }
}

TEST(GeometryPlane, IntegerClassifyMatchesOracle) {
  Gen g(4);
  const char kinds[] = {'S', 'E', 'A'};
  int zeros = 0;
  for (int i = 0; i < 30000; ++i) {
    const Plane p = g.plane(kinds[i % 3]);
    const IntPoint x = g.point();
    const int o = sign_of(dot(to_mp(p), to_mp(x)));
    EXPECT_EQ(classify(x, p), o);
    zeros += o == 0;
  }
  EXPECT_GT(zeros, 100);  // corners hit axis planes at +-2^25 exactly
  // Exact zeros: points on supporting planes at extreme coordinates.
  for (int i = 0; i < 2000; ++i) {
    const auto t = g.triangle();
    const Plane s = *supporting_plane(t[0], t[1], t[2]);
    const IntPoint m{t[0].x + t[1].x - t[2].x, t[0].y + t[1].y - t[2].y, t[0].z + t[1].z - t[2].z};
    if (!in_range(m)) continue;
    EXPECT_EQ(classify(m, s), 0);  // t0 + t1 - t2 lies in the plane
  }
}

TEST(GeometryPlane, ParallelCoplanarSameOrientationMatchOracle) {
  Gen g(5);
  const char kinds[] = {'S', 'E', 'A'};
  int par = 0, cop = 0;
  for (int i = 0; i < 6000; ++i) {
    const Plane p = g.plane(kinds[i % 3]);
    Plane q;
    switch (i % 4) {
      case 0: q = g.plane(kinds[(i / 3) % 3]); break;  // generic
      case 1: q = -p; break;                           // same plane, flipped
      case 2: {                                        // parallel, shifted
        q = p;
        q.d = OffsetCoef::assume_bound(q.d + OffsetCoef(1 + (i % 5)));
        break;
      }
      default: {  // scaled copy where it fits (normal and offset x2, possibly flipped)
        q = p;
        if (p.a.abs() < NormalCoef(std::int64_t{1} << 51) && p.b.abs() < NormalCoef(std::int64_t{1} << 51) &&
            p.c.abs() < NormalCoef(std::int64_t{1} << 51) && p.d.abs() < OffsetCoef(i128{1} << 77)) {
          q = Plane{NormalCoef::assume_bound(p.a + p.a), NormalCoef::assume_bound(p.b + p.b),
                    NormalCoef::assume_bound(p.c + p.c), OffsetCoef::assume_bound(p.d + p.d)};
          if (i % 8 == 7) q = -q;
        }
      }
    }
    const MpPlane a = to_mp(p), b = to_mp(q);
    const bool o_par = a[1] * b[2] == a[2] * b[1] && a[2] * b[0] == a[0] * b[2] && a[0] * b[1] == a[1] * b[0];
    bool o_cop = o_par;
    for (int k = 0; k < 3; ++k) o_cop = o_cop && a[k] * b[3] == b[k] * a[3];
    EXPECT_EQ(parallel(p, q), o_par);
    EXPECT_EQ(coplanar(p, q), o_cop);
    if (o_par) {
      EXPECT_EQ(same_orientation(p, q), a[0] * b[0] + a[1] * b[1] + a[2] * b[2] > 0);
    }
    par += o_par;
    cop += o_cop;
    if (i % 4 == 1) {
      EXPECT_TRUE(coplanar(p, q));
      EXPECT_FALSE(same_orientation(p, q));
    }
    if (i % 4 == 2) {
      EXPECT_TRUE(parallel(p, q));
      EXPECT_FALSE(coplanar(p, q));
      EXPECT_TRUE(same_orientation(p, q));
    }
  }
  EXPECT_GT(par, 4000);
  EXPECT_GT(cop, 2500);
}

}  // namespace
}  // namespace ember::test
