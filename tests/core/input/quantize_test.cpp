// The quantization map: power-of-two scale, exact for grid-representable
// inputs, correctly rounded export of exact rational points (GMP oracle).
#include <gmpxx.h>
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "core/route/direct/direct_faces.hpp"
#include "core/input/quantize.hpp"
#include "ember/error.hpp"
#include "support/correct_rounding.hpp"
#include "support/int_gmp.hpp"

namespace ember::test {
namespace {

TEST(Quantize, IntegerInputsMapExactlyAndBack) {
  const std::vector<Vec3d> pts{{0, 0, 0}, {3, -7, 12}, {-5, 4, 1}};
  const Quantizer q = Quantizer::fit(pts);
  for (const Vec3d& p : pts) {
    const IntPoint g = q.quantize(p);
    EXPECT_LE(std::max({std::llabs(g.x), std::llabs(g.y), std::llabs(g.z)}), Quantizer::kLimit);
    EXPECT_EQ(q.dequantize(g), p);
    EXPECT_EQ(q.dequantize(to_point(g)), p);
  }
}

TEST(Quantize, UsesTheRangeWithAPowerOfTwoScale) {
  const std::vector<Vec3d> pts{{-1.5, 0, 0}, {1.5, 0.25, 0}};
  const Quantizer q = Quantizer::fit(pts);
  const IntPoint hi = q.quantize({1.5, 0, 0});
  // Within one bit of the limit: 2^k * half extent in (kLimit/2, kLimit].
  EXPECT_GT(hi.x, Quantizer::kLimit / 2);
  EXPECT_LE(hi.x, Quantizer::kLimit);
  EXPECT_EQ(q.grid_spacing(), std::ldexp(1.0, -q.exponent()));
}

TEST(Quantize, RejectsNonFiniteCoordinates) {
  const std::vector<Vec3d> bad{{0, 0, 0}, {NAN, 1, 2}};
  EXPECT_THROW(Quantizer::fit(bad), Error);
  const std::vector<Vec3d> inf{{0, 0, 0}, {1, INFINITY, 2}};
  EXPECT_THROW(Quantizer::fit(inf), Error);
}

TEST(Quantize, RoundingErrorIsAtMostHalfAGridStep) {
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> u(-123.4, 567.8);
  std::vector<Vec3d> pts;
  for (int i = 0; i < 2000; ++i) pts.push_back({u(rng), u(rng), u(rng)});
  const Quantizer q = Quantizer::fit(pts);
  const double h = q.grid_spacing();
  for (const Vec3d& p : pts) {
    const Vec3d back = q.dequantize(q.quantize(p));
    EXPECT_LE(std::fabs(back.x - p.x), h / 2);
    EXPECT_LE(std::fabs(back.y - p.y), h / 2);
    EXPECT_LE(std::fabs(back.z - p.z), h / 2);
  }
}

/// Whether every grid point on the box of corners (+-kCoordLimit)^3 and a
/// few inside dequantize to their exact value (g + centre) * 2^-k.
bool grid_corners_dequantize_exactly(const Quantizer& q) {
  const std::int64_t L = kCoordLimit;
  for (const std::int64_t v : {-L, -L + 1, std::int64_t{-1}, std::int64_t{0}, std::int64_t{1}, L - 1, L}) {
    const Vec3d d = q.dequantize(IntPoint{v, v, v});
    for (int a = 0; a < 3; ++a) {
      mpq_class want = mpz_class(static_cast<long>(v)) + mpz_class(static_cast<long>(q.centre_grid()[a]));
      if (q.exponent() >= 0) {
        want /= mpz_class(1) << static_cast<unsigned>(q.exponent());
      } else {
        want *= mpz_class(1) << static_cast<unsigned>(-q.exponent());
      }
      if (mpq_class((&d.x)[a]) != want) return false;
    }
  }
  return true;
}

TEST(Quantize, GridPointsExactMeansTheyDequantizeExactly) {
  // Near the origin the centre is small: every grid point is a double.
  const Quantizer near = Quantizer::fit_box({-3, -1, 0}, {5, 2, 1});
  EXPECT_TRUE(near.grid_points_exact());
  EXPECT_TRUE(grid_corners_dequantize_exactly(near));
  // A unit box a long way off: the centre needs more than 53 - 26 bits more
  // than the grid, so grid points near it do not all fit a double (the mesh
  // stage then checks every output triangle's rounded area).
  const Quantizer far = Quantizer::fit_box({1e9, 1e9, 1e9}, {1e9 + 1, 1e9 + 1, 1e9 + 1});
  EXPECT_FALSE(far.grid_points_exact());
  EXPECT_FALSE(grid_corners_dequantize_exactly(far));
}

/// Exact value of a double as a rational.
mpq_class exact(double d) {
  mpq_class r(d);  // GMP converts doubles exactly
  return r;
}

TEST(Quantize, ExportOfRationalPointsIsCorrectlyRounded) {
  // Points from three random planes: compare the exported double with the
  // exact rational (X + C W) / W * 2^-k — no double is closer.
  std::mt19937_64 rng(9);
  std::uniform_int_distribution<std::int64_t> c(-(1 << 20), 1 << 20);
  const Quantizer q = Quantizer::fit_box({-3.25, 10, 0.5}, {7.75, 11, 100});
  int checked = 0;
  for (int i = 0; i < 3000; ++i) {
    const auto plane = [&] {
      return Plane{NormalCoef(c(rng)), NormalCoef(c(rng)), NormalCoef(c(rng)), OffsetCoef(c(rng) * c(rng))};
    };
    const auto x = intersect(plane(), plane(), plane());
    if (!x) continue;
    const Vec3d out = q.dequantize(*x);
    const PointXYZ* num[3] = {&x->x, &x->y, &x->z};
    const double got[3] = {out.x, out.y, out.z};
    for (int a = 0; a < 3; ++a) {
      mpz_class n(num[a]->to_string()), w(x->w.to_string());
      mpq_class value(n + mpz_class(static_cast<long>(q.centre_grid()[a])) * w, w);
      value.canonicalize();
      mpq_class scale(1);
      if (q.exponent() >= 0) {
        scale = mpq_class(1, mpz_class(1) << q.exponent());
      } else {
        scale = mpq_class(mpz_class(1) << -q.exponent());
      }
      value *= scale;
      const double d = got[a];
      const mpq_class err = abs(exact(d) - value);
      EXPECT_LE(err, abs(exact(std::nextafter(d, INFINITY)) - value));
      EXPECT_LE(err, abs(exact(std::nextafter(d, -INFINITY)) - value));
      ++checked;
    }
  }
  EXPECT_GT(checked, 6000);
}

/// The exact value of coordinate a of p in caller units: (X + C W) / W * 2^-k.
mpq_class exact_coordinate(const Quantizer& q, const Point& p, int a) {
  const PointXYZ& x = a == 0 ? p.x : (a == 1 ? p.y : p.z);
  const mpz_class w = to_mpz(p.w);
  mpq_class value(to_mpz(x) + mpz_class(static_cast<long>(q.centre_grid()[a])) * w, w);
  value.canonicalize();
  if (q.exponent() >= 0) {
    value /= mpq_class(pow2(q.exponent()));
  } else {
    value *= mpq_class(pow2(-q.exponent()));
  }
  return value;
}

::testing::AssertionResult exports_correctly(const Quantizer& q, const Point& p) {
  const Vec3d out = q.dequantize(p);
  const double got[3] = {out.x, out.y, out.z};
  for (int a = 0; a < 3; ++a)
    if (auto r = rounds_correctly(exact_coordinate(q, p, a), got[a]); !r) return r << " on axis " << a;
  return ::testing::AssertionSuccess();
}

/// A point with these i128 coordinates over w > 0.
Point small_point(__int128 x, __int128 y, __int128 z, __int128 w) {
  Point p{PointXYZ(x), PointXYZ(y), PointXYZ(z), PointW(w), {}};
  detail::cache_approx(p);
  return p;
}

/// Quantizers with the centre at 0, near 2^45 grid units and beyond 2^52 of
/// them (where dequantize must leave the double evaluation).
std::vector<Quantizer> quantizers() {
  return {Quantizer::fit_box({-3.25, 10, 0.5}, {7.75, 11, 100}), Quantizer::fit_box({-1, -1, -1}, {1, 1, 1}),
          Quantizer::fit_box({1e6, -2e6, 3e6}, {1e6 + 0.5, -2e6 + 0.25, 3e6 + 1}),
          Quantizer::fit_box({1e10, 1e10, -1e10}, {1e10 + 1, 1e10 + 1, -1e10 + 1})};
}

TEST(Quantize, ExportOfCrossingPointsIsCorrectlyRounded) {
  // The direct route's points (a (-sb) + b sa) / (sa - sb): i128 coordinates,
  // which dequantize rounds in double where that decides.
  std::mt19937_64 rng(31);
  std::uniform_int_distribution<std::int64_t> coord(-(std::int64_t{1} << 25), std::int64_t{1} << 25);
  long checked = 0;
  for (const Quantizer& q : quantizers())
    for (int i = 0; i < 3000; ++i) {
      const IntPoint a{coord(rng), coord(rng), coord(rng)}, b{coord(rng), coord(rng), coord(rng)};
      const int bits = 1 + static_cast<int>(rng() % 82);
      const auto side = [&] {
        const __int128 v = (static_cast<__int128>(rng()) << 64 | rng()) & ((static_cast<__int128>(1) << bits) - 1);
        return v == 0 ? __int128{1} : v;
      };
      const __int128 sa = side(), sb = -side();
      ASSERT_TRUE(exports_correctly(q, core::crossing_point(a, b, (i % 2) ? sa : sb, (i % 2) ? sb : sa)));
      ++checked;
    }
  EXPECT_EQ(checked, 12000);
}

TEST(Quantize, ExportNearAndAtRoundingMidpointsIsCorrectlyRounded) {
  // Coordinates X / W + C within a few 1/W of a midpoint between two
  // doubles, and exactly on one (ties to even), at grid values of every
  // size from near 0 to 2^25 and near powers of two.
  std::mt19937_64 rng(37);
  long checked = 0;
  for (const Quantizer& q : quantizers()) {
    const std::int64_t c = q.centre_grid()[0];
    for (int i = 0; i < 4000; ++i) {
      // A grid value g (relative to the centre), then the double s nearest
      // to C + g and the midpoint above or below it.
      const int magnitude = static_cast<int>(rng() % 27) - 1;  // |g| ~ 2^-1 .. 2^25
      double g = std::ldexp(static_cast<double>(rng() % 1000000) / 1000000.0 + 1.0, magnitude);
      if (i % 7 == 0) g = std::ldexp(1.0, magnitude);  // a power of two: the gap below is half
      if (rng() & 1) g = -g;
      const double s = static_cast<double>(static_cast<long double>(c) + g);
      const double neighbour = std::nextafter(s, (rng() & 1) ? INFINITY : -INFINITY);
      const mpq_class mid = (mpq_class(s) + mpq_class(neighbour)) / 2 - mpq_class(mpz_class(static_cast<long>(c)));
      // mid = p / 2^t: W = 2^t K with K random, X = p K + delta.
      const mpz_class den = mid.get_den(), num = mid.get_num();
      if (den > pow2(40)) continue;                   // values whose gap is below 2^-40 of a grid unit
      const mpz_class k = from_u64(rng() >> 24) + 1;  // below 2^40
      const int delta = static_cast<int>(rng() % 5) - 2;
      const mpz_class w = den * k, x = num * k + delta;
      const Point p = small_point(from_mpz<127>(x).raw(), from_mpz<127>(x + 1).raw(), from_mpz<127>(-x).raw(),
                                  from_mpz<127>(w).raw());
      ASSERT_TRUE(exports_correctly(q, p)) << "g " << g << " delta " << delta;
      ++checked;
    }
  }
  EXPECT_GT(checked, 12000);
  // Just below the tie under a power of two 2^m, where the gap to the double
  // below is half the gap above, with the fraction's double exactly on the
  // tie (w = 2^60 + 1 rounds down to 2^60): only the half gap below tells
  // that 2^m is not the nearest.
  const Quantizer centred = Quantizer::fit_box({-1, -1, -1}, {1, 1, 1});
  ASSERT_EQ(centred.centre_grid()[0], 0);
  for (int m = 2; m <= 25; ++m) {
    const mpz_class w = pow2(60) + 1, n = pow2(m) - 1;
    const mpz_class r = (pow2(60) - pow2(m + 6)) * w / pow2(60);  // floor((1 - 2^(m-54)) w)
    for (const int sign : {1, -1}) {
      const mpz_class x = sign * (n * w + r);
      const Point p =
          small_point(from_mpz<127>(x).raw(), from_mpz<127>(x).raw(), from_mpz<127>(x).raw(), from_mpz<127>(w).raw());
      EXPECT_TRUE(exports_correctly(centred, p)) << "m " << m << " sign " << sign;
    }
  }
}

}  // namespace
}  // namespace ember::test
