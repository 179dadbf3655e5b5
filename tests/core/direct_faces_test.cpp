// The direct route's exact arithmetic (src/core/direct_faces.hpp) against
// GMP: crossing points of a grid segment with a triangle's plane, and their
// order along the segment, at the full coordinate range.
#include <gtest/gtest.h>
#include <gmpxx.h>

#include <optional>
#include <random>

#include "core/direct_faces.hpp"
#include "geometry/oracle.hpp"
#include "support/int_gmp.hpp"

namespace ember::test {
namespace {

using core::crossing_before;
using core::crossing_point;

mpz_class mpz128(__int128 v) {
  return mpz_class(static_cast<long>(v >> 64)) * pow2(64) + from_u64(static_cast<std::uint64_t>(v));
}

using Points = Gen;  // grid points at the corners of the range, near them, or uniform

/// A segment a -> b and a triangle's plane that it crosses strictly: the
/// side values of a and b (grid_side), of opposite signs.
struct Crossing {
  IntPoint a, b;
  __int128 sa, sb;
};

/// nullopt when 100 tries found none (a plane with the whole range on one
/// side, such as a face of the range's cube).
std::optional<Crossing> random_crossing(Points& g, const std::array<IntPoint, 3>& t) {
  const std::array<std::int64_t, 3> n = grid_normal(t[0], t[1], t[2]);
  for (int tries = 0; tries < 100; ++tries) {
    const IntPoint a = g.point(), b = g.point();
    const __int128 sa = grid_side(t[0], n, a), sb = grid_side(t[0], n, b);
    if ((sa > 0 && sb < 0) || (sa < 0 && sb > 0)) return Crossing{a, b, sa, sb};
  }
  return std::nullopt;
}

std::array<IntPoint, 3> random_triangle(Points& g) {
  for (;;) {
    const std::array<IntPoint, 3> t{g.point(), g.point(), g.point()};
    if (grid_normal(t[0], t[1], t[2]) != std::array<std::int64_t, 3>{0, 0, 0}) return t;
  }
}

TEST(DirectFaces, CrossingPointIsTheExactIntersectionAtFullRange) {
  Points g(23);
  int max_w_bits = 0;
  for (int i = 0; i < 20000; ++i) {
    const std::array<IntPoint, 3> t = random_triangle(g);
    const std::optional<Crossing> found = random_crossing(g, t);
    if (!found) continue;
    const Crossing& c = *found;
    const Point p = crossing_point(c.a, c.b, c.sa, c.sb);
    const mpz_class w = to_mpz(p.w);
    ASSERT_GT(w, 0);
    // p = a + (b - a) sa / (sa - sb), as a rational with denominator sa - sb.
    const mpz_class d = mpz128(c.sa) - mpz128(c.sb);
    const std::int64_t pa[3] = {c.a.x, c.a.y, c.a.z}, pb[3] = {c.b.x, c.b.y, c.b.z};
    const PointXYZ* xyz[3] = {&p.x, &p.y, &p.z};
    for (int k = 0; k < 3; ++k) {
      const mpz_class num = mpz_class(static_cast<long>(pa[k])) * d +
                            (mpz_class(static_cast<long>(pb[k])) - static_cast<long>(pa[k])) * mpz128(c.sa);
      ASSERT_EQ(to_mpz(*xyz[k]) * d, num * w) << "coordinate " << k;
    }
    // It lies on the plane: n . (p - t0) = 0.
    const std::array<std::int64_t, 3> n = grid_normal(t[0], t[1], t[2]);
    const mpz_class on = mpz_class(static_cast<long>(n[0])) * (to_mpz(p.x) - w * static_cast<long>(t[0].x)) +
                         mpz_class(static_cast<long>(n[1])) * (to_mpz(p.y) - w * static_cast<long>(t[0].y)) +
                         mpz_class(static_cast<long>(n[2])) * (to_mpz(p.z) - w * static_cast<long>(t[0].z));
    ASSERT_EQ(on, 0);
    max_w_bits = std::max(max_w_bits, static_cast<int>(mpz_sizeinbase(w.get_mpz_t(), 2)));
  }
  EXPECT_GE(max_w_bits, 80);  // side values near the 2^82 bound
}

TEST(DirectFaces, CrossingOrderMatchesTheRationalParameters) {
  // Two planes crossing one segment: which crossing comes first from a.
  // A third of the second planes are the first one again (equal
  // parameters: neither comes before the other).
  Points g(23);
  int ties = 0;
  for (int i = 0; i < 20000; ++i) {
    const std::array<IntPoint, 3> t = random_triangle(g);
    const std::optional<Crossing> found = random_crossing(g, t);
    if (!found) continue;
    const Crossing& x = *found;
    std::array<IntPoint, 3> u = i % 3 == 0 ? t : random_triangle(g);
    const std::array<std::int64_t, 3> nu = grid_normal(u[0], u[1], u[2]);
    const __int128 ya = grid_side(u[0], nu, x.a), yb = grid_side(u[0], nu, x.b);
    if (!((ya > 0 && yb < 0) || (ya < 0 && yb > 0))) continue;
    // lambda = sa / (sa - sb) in (0, 1); compare exactly.
    mpq_class lx(mpz128(x.sa), mpz128(x.sa) - mpz128(x.sb)), ly(mpz128(ya), mpz128(ya) - mpz128(yb));
    lx.canonicalize();
    ly.canonicalize();
    ASSERT_EQ(crossing_before(x.sa, x.sb, ya, yb), lx < ly);
    ASSERT_EQ(crossing_before(ya, yb, x.sa, x.sb), ly < lx);
    ties += lx == ly;
  }
  EXPECT_GE(ties, 1000);
}

}  // namespace
}  // namespace ember::test
