// The quantization map: power-of-two scale, exact for grid-representable
// inputs, correctly rounded export of exact rational points (GMP oracle).
#include <gmpxx.h>
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "ember/core/quantize.hpp"
#include "ember/error.hpp"

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

}  // namespace
}  // namespace ember::test
