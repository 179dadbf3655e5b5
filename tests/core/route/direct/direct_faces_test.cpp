// The direct route's exact arithmetic (src/core/direct_faces.hpp) against
// GMP: crossing points of a grid segment with a triangle's plane, their
// order along the segment, and the chord of two meeting triangles, at the
// full coordinate range and on a tiny grid full of degenerate contacts.
#include <gtest/gtest.h>
#include <gmpxx.h>

#include <optional>
#include <random>

#include "support/contact_fixtures.hpp"
#include "core/route/direct/direct_faces.hpp"
#include "support/geometry_oracle.hpp"
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

/// The rational oracle's view of two triangles x (operand 0) and y
/// (operand 1): what pair_chord must answer.
struct OracleChord {
  bool general = false;                      ///< in general position, crossing along one chord
  std::array<core::CrossingName, 2> ends{};  ///< start, then end along n_x x n_y
};

using Vec = std::array<mpq_class, 3>;
Vec vec(const IntPoint& p) {
  return {mpq_class(static_cast<long>(p.x)), mpq_class(static_cast<long>(p.y)), mpq_class(static_cast<long>(p.z))};
}
Vec sub(const Vec& a, const Vec& b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }
Vec cross(const Vec& a, const Vec& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
mpq_class dot(const Vec& a, const Vec& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

/// Rational: the points where one triangle's edges cross the other's plane
/// strictly, kept if strictly inside the other; any such point on the
/// other's boundary, or a corner on the other's plane, is not general position.
OracleChord oracle_chord(const std::array<IntPoint, 3>& x, const std::array<IntPoint, 3>& y,
                         const core::EdgeNames& names) {
  const std::array<const std::array<IntPoint, 3>*, 2> tri{&x, &y};
  std::array<Vec, 2> normal;
  for (int k = 0; k < 2; ++k) {
    const auto& t = *tri[static_cast<std::size_t>(k)];
    normal[static_cast<std::size_t>(k)] = cross(sub(vec(t[1]), vec(t[0])), sub(vec(t[2]), vec(t[0])));
  }
  OracleChord out;
  std::vector<std::pair<core::CrossingName, Vec>> inside;
  for (int k = 0; k < 2; ++k) {
    const auto &t = *tri[static_cast<std::size_t>(k)], &o = *tri[static_cast<std::size_t>(1 - k)];
    const Vec& no = normal[static_cast<std::size_t>(1 - k)];
    mpq_class side[3];
    for (int i = 0; i < 3; ++i) {
      side[i] = dot(no, sub(vec(t[static_cast<std::size_t>(i)]), vec(o[0])));
      if (side[i] == 0) return out;  // a corner on the other's plane
    }
    for (int i = 0; i < 3; ++i) {
      const int j = (i + 1) % 3;
      if ((side[i] > 0) == (side[j] > 0)) continue;
      const Vec a = vec(t[static_cast<std::size_t>(i)]), b = vec(t[static_cast<std::size_t>(j)]);
      const mpq_class lambda = side[i] / (side[i] - side[j]);
      const Vec p{a[0] + (b[0] - a[0]) * lambda, a[1] + (b[1] - a[1]) * lambda, a[2] + (b[2] - a[2]) * lambda};
      int positive = 0, zero = 0;
      for (int e = 0; e < 3; ++e) {
        const Vec u = vec(o[static_cast<std::size_t>(e)]), v = vec(o[static_cast<std::size_t>((e + 1) % 3)]);
        const int s = sgn(dot(cross(sub(v, u), sub(p, u)), no));
        positive += s > 0;
        zero += s == 0;
      }
      if (positive + zero == 3 && zero > 0) return out;  // on the other's boundary
      if (positive == 3)
        inside.push_back({{names.edge_key(static_cast<std::uint32_t>(k), i), static_cast<std::uint32_t>(1 - k)}, p});
    }
  }
  if (inside.size() != 2) return out;
  const Vec d = cross(normal[0], normal[1]);
  if (dot(sub(inside[1].second, inside[0].second), d) < 0) std::swap(inside[0], inside[1]);
  out.general = true;
  out.ends = {inside[0].first, inside[1].first};
  return out;
}

TEST(DirectFaces, PairChordMatchesTheRationalIntersection) {
  // Triangles x (id 0, operand 0) and y (id 1, operand 1) with their own
  // vertex ids; on a 7^3 grid most meeting pairs touch degenerately
  // (corners on planes, crossings on edges, the line through a third edge).
  core::GridTriangles grid;
  grid.corners.resize(2);
  const std::vector<std::array<std::uint32_t, 3>> ids{{0, 1, 2}, {0, 1, 2}};
  core::InputTopology topo;
  topo.by_triangle = ids;
  topo.operand_base = {0, 3, 6};
  const std::vector<std::uint32_t> operand_of{0, 1};
  const core::EdgeNames names{topo, operand_of};
  Points g(29);
  int general = 0, degenerate = 0;
  for (int i = 0; i < 40000; ++i) {
    const bool tiny = i % 2 == 0;
    const auto triangle = [&] {
      for (;;) {
        const std::array<IntPoint, 3> t =
            tiny ? std::array<IntPoint, 3>{g.small_point(3), g.small_point(3), g.small_point(3)} : random_triangle(g);
        if (grid_normal(t[0], t[1], t[2]) != std::array<std::int64_t, 3>{0, 0, 0}) return t;
      }
    };
    grid.corners[0] = triangle();
    grid.corners[1] = triangle();
    set_normals(grid);
    const OracleChord want = oracle_chord(grid.corners[0], grid.corners[1], names);
    core::PairChord got;
    ASSERT_EQ(core::pair_chord(grid, names, 0, 1, got), want.general) << "pair " << i;
    if (!want.general) {
      ++degenerate;
      continue;
    }
    ++general;
    ASSERT_EQ(got.end[0].name, want.ends[0]) << "pair " << i;
    ASSERT_EQ(got.end[1].name, want.ends[1]) << "pair " << i;
  }
  EXPECT_GT(general, 2000);
  EXPECT_GT(degenerate, 2000);
}

}  // namespace
}  // namespace ember::test
