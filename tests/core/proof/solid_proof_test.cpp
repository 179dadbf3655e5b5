// The exact solid proof (src/core/solid_check.hpp): the pairwise contact
// predicate on hand-made configurations and random small-grid triangles, and
// the verdict on procedural shapes whose solidity is known by construction.
#include <gtest/gtest.h>

#include <gmpxx.h>
#include <tbb/task_arena.h>

#include <functional>
#include <random>

#include "core/model/grid_triangles.hpp"
#include "core/model/components.hpp"
#include "core/search/triangle_contact.hpp"
#include "core/support/fill_vector.hpp"
#include "support/boolean_checks.hpp"

namespace ember::test {
namespace {

using Tri = std::array<IntPoint, 3>;
using core::triangles_meet_improperly;

/// The predicate must not depend on vertex order, orientation or argument order.
bool meet(const Tri& a, const Tri& b) {
  const bool r = triangles_meet_improperly(a, b);
  const Tri ar{a[1], a[2], a[0]}, br{b[2], b[0], b[1]}, af{a[0], a[2], a[1]}, bf{b[1], b[0], b[2]};
  EXPECT_EQ(triangles_meet_improperly(b, a), r);
  EXPECT_EQ(triangles_meet_improperly(ar, br), r);
  EXPECT_EQ(triangles_meet_improperly(af, b), r);
  EXPECT_EQ(triangles_meet_improperly(a, bf), r);
  return r;
}

TEST(TriangleContact, NoSharedVertex) {
  const Tri a{{{0, 0, 0}, {4, 0, 0}, {0, 4, 0}}};
  EXPECT_FALSE(meet(a, {{{0, 0, 1}, {4, 0, 1}, {0, 4, 1}}}));    // parallel planes
  EXPECT_TRUE(meet(a, {{{1, 1, -1}, {1, 1, 1}, {2, 0, 5}}}));    // pierces the interior
  EXPECT_FALSE(meet(a, {{{3, 3, -1}, {3, 3, 1}, {4, 4, 0}}}));   // crosses the plane outside a
  EXPECT_TRUE(meet(a, {{{1, 1, 0}, {1, 1, 3}, {2, 2, 3}}}));     // a vertex touches a's interior
  EXPECT_TRUE(meet(a, {{{2, 0, 0}, {2, -1, 3}, {2, 1, 3}}}));    // a vertex touches a's edge
  EXPECT_TRUE(meet(a, {{{1, 1, 0}, {5, 1, 0}, {1, 5, 0}}}));     // coplanar overlap
  EXPECT_FALSE(meet(a, {{{3, 3, 0}, {6, 3, 0}, {3, 6, 0}}}));    // coplanar, disjoint
  EXPECT_TRUE(meet(a, {{{2, 2, 0}, {6, 2, 0}, {2, 6, 0}}}));     // coplanar, touching at a point
  EXPECT_TRUE(meet(a, {{{-1, 2, -1}, {-1, 2, 1}, {3, 0, 0}}}));  // an edge of b crosses a's edge region
}

TEST(TriangleContact, SharedEdge) {
  const Tri a{{{0, 0, 0}, {4, 0, 0}, {0, 4, 0}}};
  EXPECT_FALSE(meet(a, {{{4, 0, 0}, {0, 0, 0}, {1, -3, 2}}}));  // fold
  EXPECT_FALSE(meet(a, {{{4, 0, 0}, {0, 0, 0}, {1, -3, 0}}}));  // flat, opposite sides
  EXPECT_TRUE(meet(a, {{{4, 0, 0}, {0, 0, 0}, {1, 1, 0}}}));    // flat, folded onto a
  EXPECT_TRUE(meet(a, {{{0, 0, 0}, {4, 0, 0}, {0, 4, 0}}}));    // the same triangle
  EXPECT_TRUE(meet(a, {{{4, 0, 0}, {0, 0, 0}, {0, 4, 0}}}));    // the same triangle, reversed
}

TEST(TriangleContact, SharedVertex) {
  const Tri a{{{0, 0, 0}, {4, 0, 0}, {0, 4, 0}}};
  EXPECT_FALSE(meet(a, {{{0, 0, 0}, {-1, -1, 2}, {-2, 1, 3}}}));    // apart, not coplanar
  EXPECT_FALSE(meet(a, {{{0, 0, 0}, {1, 1, 2}, {2, 1, 3}}}));       // above a, touching only at v
  EXPECT_TRUE(meet(a, {{{0, 0, 0}, {1, 1, 2}, {2, 1, -3}}}));       // crosses a's plane inside a
  EXPECT_FALSE(meet(a, {{{0, 0, 0}, {-1, -1, 2}, {-1, -1, -2}}}));  // crosses a's plane outside a
  EXPECT_TRUE(meet(a, {{{0, 0, 0}, {2, 2, 0}, {1, 1, 3}}}));        // an edge of b lies in a
  EXPECT_FALSE(meet(a, {{{0, 0, 0}, {-3, 0, 0}, {0, -3, 0}}}));     // coplanar, opposite wedge
  EXPECT_TRUE(meet(a, {{{0, 0, 0}, {1, 1, 0}, {-1, 3, 0}}}));       // coplanar, wedges overlap
  EXPECT_TRUE(meet(a, {{{0, 0, 0}, {0, 2, 0}, {-3, 1, 0}}}));       // coplanar, touching along an edge ray
  EXPECT_FALSE(meet(a, {{{0, 0, 0}, {0, 4, 0}, {-3, 1, 0}}}));      // (shares an edge: flat, opposite sides)
}

/// Independent oracle in exact rationals: computes A ∩ B as a convex set
/// (the part of B in A's plane, clipped by A's edge half-planes) and asks
/// whether it has a vertex that is neither a shared vertex nor on a shared edge.
using Q3 = std::array<mpq_class, 3>;
Q3 q3(const IntPoint& p) { return {mpq_class(p.x), mpq_class(p.y), mpq_class(p.z)}; }
Q3 sub(const Q3& a, const Q3& b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }
Q3 crs(const Q3& a, const Q3& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
mpq_class dt(const Q3& a, const Q3& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
Q3 lerp(const Q3& a, const Q3& b, const mpq_class& t) {
  return {a[0] + t * (b[0] - a[0]), a[1] + t * (b[1] - a[1]), a[2] + t * (b[2] - a[2])};
}

/// Keeps the part of the convex polygon `poly` (possibly degenerate) where f >= 0.
std::vector<Q3> clip_keep(const std::vector<Q3>& poly, const std::function<mpq_class(const Q3&)>& f) {
  std::vector<Q3> out;
  const std::size_t n = poly.size();
  for (std::size_t i = 0; i < n; ++i) {
    const Q3 &p = poly[i], &q = poly[(i + 1) % n];
    const mpq_class fp = f(p), fq = f(q);
    if (fp >= 0) out.push_back(p);
    if ((fp > 0 && fq < 0) || (fp < 0 && fq > 0)) out.push_back(lerp(p, q, fp / (fp - fq)));
  }
  return out;
}

/// With `any`: whether the closed triangles have any common point.
bool oracle_meet(const Tri& a, const Tri& b, bool any = false) {
  const Q3 A[3] = {q3(a[0]), q3(a[1]), q3(a[2])};
  const Q3 nA = crs(sub(A[1], A[0]), sub(A[2], A[0]));
  std::vector<Q3> set{q3(b[0]), q3(b[1]), q3(b[2])};
  const auto plane = [&](const Q3& x) { return dt(nA, sub(x, A[0])); };
  set = clip_keep(set, plane);
  // mpq_class, not the expression template of a negated temporary (dangling).
  set = clip_keep(set, [&](const Q3& x) -> mpq_class { return -plane(x); });  // B in A's plane
  for (int i = 0; i < 3 && !set.empty(); ++i) {
    const Q3 inward = crs(nA, sub(A[(i + 1) % 3], A[i]));
    set = clip_keep(set, [&](const Q3& x) { return dt(inward, sub(x, A[i])); });
  }
  if (any) return !set.empty();
  std::vector<Q3> shared;
  for (const IntPoint& p : a)
    for (const IntPoint& q : b)
      if (p == q) shared.push_back(q3(p));
  if (shared.size() == 3) return !set.empty();
  for (const Q3& x : set) {
    bool allowed = false;
    for (const Q3& s : shared) allowed |= x == s;
    if (shared.size() == 2) {  // on the shared segment?
      const Q3 d = sub(shared[1], shared[0]), e = sub(x, shared[0]);
      const Q3 c = crs(d, e);
      allowed |= c[0] == 0 && c[1] == 0 && c[2] == 0 && dt(d, e) >= 0 && dt(d, e) <= dt(d, d);
    }
    if (!allowed) return true;
  }
  return false;
}

/// Random triangles on a lattice whose points are origin + c * step (c in
/// 0 .. points - 1 per axis), checked against the rational oracle. On so few
/// points degeneracies (shared vertices and edges, coplanarity, touching) are
/// frequent. meet() also checks argument and vertex symmetries. Every third
/// pair is forced to share a vertex unless `unshared`, which instead skips
/// pairs with a common vertex (the straddle test's territory).
void expect_random_lattice_pairs_match_oracle(std::int64_t origin, std::int64_t step, int points = 4, int pairs = 20000,
                                              bool unshared = false) {
  std::mt19937 rng(42);
  std::uniform_int_distribution<int> c(0, points - 1);
  const auto random_point = [&] {
    return IntPoint{origin + c(rng) * step, origin + c(rng) * step, origin + c(rng) * step};
  };
  const auto degenerate = [](const Tri& t) {
    const mpz_class ux = t[1].x - t[0].x, uy = t[1].y - t[0].y, uz = t[1].z - t[0].z;
    const mpz_class vx = t[2].x - t[0].x, vy = t[2].y - t[0].y, vz = t[2].z - t[0].z;
    return uy * vz - uz * vy == 0 && uz * vx - ux * vz == 0 && ux * vy - uy * vx == 0;
  };
  int tested = 0, met = 0, shared_vertex = 0, mismatches = 0;
  const auto share = [](const Tri& a, const Tri& b) {
    for (const IntPoint& p : a)
      for (const IntPoint& q : b)
        if (p == q) return true;
    return false;
  };
  while (tested < pairs) {
    const Tri a{{random_point(), random_point(), random_point()}};
    Tri b{{random_point(), random_point(), random_point()}};
    if (!unshared && tested % 3 == 0) b[0] = a[tested % 2];  // force shared vertices often
    if (degenerate(a) || degenerate(b) || (unshared && share(a, b))) continue;
    ++tested;
    const bool m = meet(a, b);
    met += m;
    shared_vertex += a[0] == b[0] || a[1] == b[0] || a[2] == b[0];
    if (m != oracle_meet(a, b)) ++mismatches;
  }
  EXPECT_EQ(mismatches, 0);
  EXPECT_GT(met, pairs / 20);
  EXPECT_LT(met, tested - pairs / 20);
  if (!unshared) {
    EXPECT_GT(shared_vertex, pairs / 7);
  }
}

TEST(TriangleContact, RandomSmallGridTrianglesMatchRationalOracle) { expect_random_lattice_pairs_match_oracle(0, 1); }

TEST(TriangleContact, RandomUnsharedLatticePairsMatchRationalOracle) {
  // Pairs without a common vertex that cross each other's planes go through
  // the two-orientation straddle test; a 3x3x3 and a 5x5x5 lattice give
  // vertices on the other plane, edges through the other's edges and
  // vertices, and touching at a single point in every arrangement.
  expect_random_lattice_pairs_match_oracle(0, 1, 3, 20000, true);
  expect_random_lattice_pairs_match_oracle(-2, 1, 5, 30000, true);
}

/// meet(a, b) against the rational oracle where any common point counts,
/// on random pairs from the 4x4x4 lattice origin + {0, 1, 2, 3} step per
/// axis (touching, corners on planes, edges through edges in every
/// arrangement), half of them sharing a vertex position.
template <typename Meet>
void expect_any_contact_matches_oracle(std::int64_t origin, std::int64_t step, std::uint32_t seed, Meet&& meet) {
  std::mt19937 rng(seed);
  std::uniform_int_distribution<int> c(0, 3);
  const auto coordinate = [&] { return origin + c(rng) * step; };
  const auto random_point = [&] {
    const std::int64_t x = coordinate(), y = coordinate();
    return IntPoint{x, y, coordinate()};
  };
  int tested = 0, met = 0, mismatches = 0;
  while (tested < 20000) {
    const Tri a{{random_point(), random_point(), random_point()}};
    Tri b{{random_point(), random_point(), random_point()}};
    if (tested % 2 == 0) b[tested % 3] = a[(tested / 2) % 3];
    if (grid_normal(a[0], a[1], a[2]) == std::array<std::int64_t, 3>{} ||
        grid_normal(b[0], b[1], b[2]) == std::array<std::int64_t, 3>{})
      continue;
    ++tested;
    const bool m = meet(a, b);
    EXPECT_EQ(m, meet(b, a));
    met += m;
    mismatches += m != oracle_meet(a, b, true);
  }
  EXPECT_EQ(mismatches, 0) << "step " << step;
  EXPECT_GT(met, 2000) << "step " << step;
  EXPECT_LT(met, tested - 2000) << "step " << step;
}

TEST(TriangleContact, AnyContactOfDifferentOperandsMatchesRationalOracle) {
  // triangles_meet (the contact test of triangles of different operands).
  expect_any_contact_matches_oracle(0, 1, 7, [](const Tri& a, const Tri& b) { return core::triangles_meet(a, b); });
}

/// The exact side of p against the plane of t, in GMP integers.
int gmp_side(const Tri& t, const IntPoint& p) {
  const auto z = [](std::int64_t v) { return mpz_class(static_cast<long>(v)); };
  const mpz_class ux = z(t[1].x) - z(t[0].x), uy = z(t[1].y) - z(t[0].y), uz = z(t[1].z) - z(t[0].z);
  const mpz_class vx = z(t[2].x) - z(t[0].x), vy = z(t[2].y) - z(t[0].y), vz = z(t[2].z) - z(t[0].z);
  const mpz_class d = (uy * vz - uz * vy) * (z(p.x) - z(t[0].x)) + (uz * vx - ux * vz) * (z(p.y) - z(t[0].y)) +
                      (ux * vy - uy * vx) * (z(p.z) - z(t[0].z));
  return sgn(d);
}

/// A triangle a with corners up to 2^24 apart anywhere in the grid, and
/// points exactly on its plane far from a's corners (a0 +- (d1 + d2)): the
/// normal near 2^50 and the sides' products far past 2^53.
struct OnPlaneCase {
  Tri a;
  IntPoint on, far;
};
OnPlaneCase on_plane_case(std::mt19937& rng) {
  std::uniform_int_distribution<std::int64_t> at(-(1 << 24), 1 << 24), d(-(1 << 23), 1 << 23);
  const IntPoint a0{at(rng), at(rng), at(rng)}, d1{d(rng), d(rng), d(rng)}, d2{d(rng), d(rng), d(rng)};
  return {Tri{{a0, {a0.x + d1.x, a0.y + d1.y, a0.z + d1.z}, {a0.x + d2.x, a0.y + d2.y, a0.z + d2.z}}},
          {a0.x + d1.x + d2.x, a0.y + d1.y + d2.y, a0.z + d1.z + d2.z},
          {a0.x - d1.x - d2.x, a0.y - d1.y - d2.y, a0.z - d1.z - d2.z}};
}

TEST(TriangleContact, BesidePlaneMatchesTheGmpSides) {
  // beside_plane (the solid path's cheap rejection) against GMP sides, on a
  // lattice where corners on the plane abound and at full-range coordinates
  // (normals near 2^53, sides near 2^82), including corners exactly on the
  // plane far from the origin.
  for (const std::int64_t range : {std::int64_t{2}, kCoordLimit}) {
    std::mt19937 rng(static_cast<std::uint32_t>(range) + 3);
    std::uniform_int_distribution<std::int64_t> c(-range, range);
    const auto pt = [&] { return IntPoint{c(rng), c(rng), c(rng)}; };
    int apart = 0, tested = 0;
    for (int n = 0; n < 30000; ++n) {
      const Tri a{{pt(), pt(), pt()}}, b{{pt(), pt(), pt()}};
      const std::array<std::int64_t, 3> na = grid_normal(a[0], a[1], a[2]);
      if (na == std::array<std::int64_t, 3>{} || grid_normal(b[0], b[1], b[2]) == std::array<std::int64_t, 3>{})
        continue;
      const int s0 = gmp_side(a, b[0]), s1 = gmp_side(a, b[1]), s2 = gmp_side(a, b[2]);
      const bool want = s0 != 0 && s0 == s1 && s1 == s2;
      ++tested;
      apart += want;
      ASSERT_EQ(core::beside_plane(a, na, b), want) << "range " << range;
      if (want) {
        EXPECT_FALSE(core::triangles_meet(a, b));
      }
    }
    EXPECT_GT(apart, tested / 10) << "range " << range;
    EXPECT_LT(apart, tested - tested / 10) << "range " << range;
  }
  std::mt19937 rng(17);
  std::uniform_int_distribution<std::int64_t> at(-(1 << 24), 1 << 24);
  int on_plane_cases = 0;
  for (int n = 0; n < 20000; ++n) {
    const auto [a, on, far] = on_plane_case(rng);
    const Tri b{{on, {at(rng), at(rng), at(rng)}, {at(rng), at(rng), at(rng)}}};
    const std::array<std::int64_t, 3> na = grid_normal(a[0], a[1], a[2]);
    if (na == std::array<std::int64_t, 3>{}) continue;
    ASSERT_EQ(gmp_side(a, on), 0);
    if (gmp_side(a, b[1]) != gmp_side(a, b[2])) continue;
    ++on_plane_cases;
    EXPECT_FALSE(core::beside_plane(a, na, b));
  }
  EXPECT_GT(on_plane_cases, 5000);
}

/// The pair test the partner search runs: PlaneSideFilter's signs of b
/// against a's plane, then apart_triangles_meet from those signs.
bool meet_from_filtered_signs(const Tri& a, const Tri& b) {
  const std::array<std::int64_t, 3> na = grid_normal(a[0], a[1], a[2]);
  const core::CornerSigns sides = core::PlaneSideFilter(a[0], na).signs(b);
  return !sides.strictly_one_side() && core::apart_triangles_meet(a, na, b, grid_normal(b[0], b[1], b[2]), sides);
}

TEST(TriangleContact, PlaneSideFilterSignsAreTheGmpSigns) {
  // PlaneSideFilter decides a corner in double only outside its error
  // margin, else exactly: its signs are GMP's, always. Random triangles from
  // tiny to full-range coordinates (normals near 2^53, products near 2^80,
  // rounded in double).
  for (const std::int64_t range : {std::int64_t{2}, std::int64_t{1} << 12, kCoordLimit}) {
    std::mt19937 rng(static_cast<std::uint32_t>(range) + 11);
    std::uniform_int_distribution<std::int64_t> c(-range, range);
    const auto pt = [&] { return IntPoint{c(rng), c(rng), c(rng)}; };
    int beside = 0, on_plane = 0;
    for (int n = 0; n < 30000; ++n) {
      const Tri a{{pt(), pt(), pt()}}, b{{pt(), pt(), pt()}};
      const std::array<std::int64_t, 3> na = grid_normal(a[0], a[1], a[2]);
      if (na == std::array<std::int64_t, 3>{}) continue;
      const core::CornerSigns got = core::PlaneSideFilter(a[0], na).signs(b);
      for (int k = 0; k < 3; ++k) {
        ASSERT_EQ(got.s[k], gmp_side(a, b[static_cast<std::size_t>(k)])) << "range " << range;
        on_plane += got.s[k] == 0;
      }
      beside += got.strictly_one_side();
    }
    EXPECT_GT(beside, 5000) << "range " << range;
    if (range == 2) {
      EXPECT_GT(on_plane, 1000);
    }
  }
  // Corners exactly on the plane, far from a's corners (differences near
  // 2^25, normals near 2^50: the rounded side is not zero, and must stay
  // within the margin): sign 0.
  std::mt19937 rng(23);
  std::uniform_int_distribution<std::int64_t> at(-(1 << 24), 1 << 24);
  int on_plane = 0;
  for (int n = 0; n < 20000; ++n) {
    const auto [a, on, far] = on_plane_case(rng);
    const std::array<std::int64_t, 3> na = grid_normal(a[0], a[1], a[2]);
    if (na == std::array<std::int64_t, 3>{}) continue;
    const Tri b{{on, far, {at(rng), at(rng), at(rng)}}};
    const core::CornerSigns got = core::PlaneSideFilter(a[0], na).signs(b);
    ASSERT_EQ(got.s[0], 0);
    ASSERT_EQ(got.s[1], 0);
    ASSERT_EQ(got.s[2], gmp_side(a, b[2]));
    ++on_plane;
  }
  EXPECT_GT(on_plane, 19000);
  // Sides of magnitude 1-3 against a normal of 2^50, (1, -P, P Q), whose
  // products cancel to them: left to the exact side.
  constexpr std::int64_t P = (std::int64_t{1} << 25) - 1, Q = (std::int64_t{1} << 25) - 3;
  const Tri a{{IntPoint{0, 0, 0}, IntPoint{P, 1, 0}, IntPoint{0, Q, 1}}};
  const std::array<std::int64_t, 3> na = grid_normal(a[0], a[1], a[2]);
  ASSERT_EQ(na, (std::array<std::int64_t, 3>{1, -P, P * Q}));
  const Tri near{{IntPoint{1, Q, 1}, IntPoint{-3, Q, 1}, IntPoint{0, Q, 1}}};
  const core::CornerSigns got = core::PlaneSideFilter(a[0], na).signs(near);
  EXPECT_EQ(got.s[0], 1);
  EXPECT_EQ(got.s[1], -1);
  EXPECT_EQ(got.s[2], 0);
}

TEST(TriangleContact, MeetFromFilteredSignsMatchesRationalOracle) {
  // The partner search's pair test, on the small lattice and stretched over
  // the whole grid (normals near 2^53: the filter's double sides rounded).
  expect_any_contact_matches_oracle(0, 1, 5, meet_from_filtered_signs);
  expect_any_contact_matches_oracle(-kCoordLimit, (2 * kCoordLimit - 1) / 3, 6, meet_from_filtered_signs);
}

TEST(TriangleContact, RandomFullRangeTrianglesMatchRationalOracle) {
  // The same lattice stretched over the whole grid, -2^25 .. 2^25 - 1: corner
  // differences near 2^26 and normal components near 2^53, the limits of the
  // int64 normal and the 128-bit side test (triangle_contact.cpp's bit budget).
  constexpr std::int64_t lo = -kCoordLimit, step = (2 * kCoordLimit - 1) / 3;
  static_assert(lo + 3 * step <= kCoordLimit && step > (std::int64_t{1} << 24));
  expect_random_lattice_pairs_match_oracle(lo, step);
}

/// The Boolean's verdict through its statistics.
std::size_t solid_operands(std::vector<Mesh> ops) {
  ops = snapped(std::move(ops));
  return run_checked(ops, Operation::Union).stats.solid_operands;
}

TEST(SolidProof, ClosedOutwardShapesAreSolid) {
  EXPECT_EQ(solid_operands({icosphere({0, 0, 0}, 1.0, 3), torus({0.5, 0, 0}, 1.0, 0.3, 32, 12)}), 2u);
  EXPECT_EQ(solid_operands({tessellated_box({0, 0, 0}, {1, 1, 1}, 4), box({0.5, 0.5, 0.5}, {2, 2, 2})}), 2u);
  // Several disjoint components, and a hollow ball (inner shell inverted).
  const Mesh two = merge({icosphere({0, 0, 0}, 1.0, 2), icosphere({3, 0, 0}, 1.0, 2)});
  const Mesh hollow = merge({icosphere({0, 0, 0}, 1.0, 2), reverse_orientation(icosphere({0, 0, 0}, 0.5, 2))});
  EXPECT_EQ(solid_operands({two, hollow}), 2u);
}

/// One trace per component, each through the operand's tree: an operand of
/// 1,728 disjoint boxes is proven too (components x soup size = 1,728 x
/// 20,748 > 2^25, past the budget of traces that scan the whole soup,
/// which used to leave it unproven).
TEST(SolidProof, AnOperandOfManyComponentsIsProven) {
  std::vector<Mesh> boxes;
  for (int x = 0; x < 12; ++x)
    for (int y = 0; y < 12; ++y)
      for (int z = 0; z < 12; ++z) boxes.push_back(box({1.0 * x, 1.0 * y, 1.0 * z}, {x + 0.5, y + 0.5, z + 0.5}));
  const Mesh many = merge(boxes);
  ASSERT_EQ(many.face_count(), 1728u * 12);
  const BooleanResult r = run_checked({many, box({2.25, 2.25, 2.25}, {7.25, 7.25, 7.25})}, Operation::Union);
  EXPECT_EQ(r.stats.operands[0].solid, SolidStatus::Proven);
  EXPECT_EQ(r.stats.solid_operands, 2u);
  EXPECT_TRUE(r.warnings.empty());
}

TEST(SolidProof, RejectsWhatTheShortcutsCannotHandle) {
  const Mesh ball = icosphere({0, 0, 0}, 1.0, 2);
  const Mesh other = box({-2, -2, -2}, {-1.5, -1.5, -1.5});
  // Two overlapping balls in one mesh: self-intersecting.
  EXPECT_EQ(solid_operands({merge({ball, icosphere({0.5, 0, 0}, 1.0, 2)}), other}), 1u);
  // Nested, same orientation: winding number 2 inside the inner ball.
  EXPECT_EQ(solid_operands({merge({ball, icosphere({0, 0, 0}, 0.5, 2)}), other}), 1u);
  // Inside out: winding number -1.
  EXPECT_EQ(solid_operands({reverse_orientation(ball), other}), 1u);
  // Two boxes sharing a face: doubled internal faces.
  EXPECT_EQ(solid_operands({merge({box({0, 0, 0}, {1, 1, 1}), box({1, 0, 0}, {2, 1, 1})}), other}), 1u);
}

TEST(SolidProof, ProofAndPromiseGiveTheSameResult) {
  const std::vector<Mesh> ops =
      snapped({icosphere({0, 0, 0}, 1.0, 3), rotate(torus({0.4, 0.1, 0.0}, 0.9, 0.3, 40, 16), random_rotation(9))});
  BooleanOptions promise;
  promise.all_solid = true;
  promise.detect_solid = false;
  for (Operation op : {Operation::Union, Operation::Intersection, Operation::Difference}) {
    const BooleanResult proven = run_checked(ops, op);
    const BooleanResult promised = run_checked(ops, op, promise);
    EXPECT_EQ(proven.stats.solid_operands, 2u);
    EXPECT_EQ(proven.mesh, promised.mesh) << int(op);  // same flags, same computation
  }
}

// The concurrent union-find must give the serial answer (per kept triangle,
// the smallest id of its component across kept neighbours) at any thread
// count: random neighbour graphs with long chains (deep trees, many
// concurrent links) and random kept subsets, against a breadth-first search.
TEST(NeighbourComponents, MatchTheSerialAnswerAtAnyThreadCount) {
  std::mt19937 rng(17);
  for (const std::size_t n : {std::size_t{1}, std::size_t{50}, std::size_t{20000}}) {
    core::GridTriangles grid;
    grid.neighbors.assign(n, {core::kNoNeighbor, core::kNoNeighbor, core::kNoNeighbor});
    std::vector<int> slots(n, 0);
    std::uniform_int_distribution<std::size_t> any(0, n - 1);
    const auto link = [&](std::size_t a, std::size_t b) {
      if (a == b || slots[a] == 3 || slots[b] == 3) return;
      grid.neighbors[a][static_cast<std::size_t>(slots[a]++)] = static_cast<std::uint32_t>(b);
      grid.neighbors[b][static_cast<std::size_t>(slots[b]++)] = static_cast<std::uint32_t>(a);
    };
    for (std::size_t i = 0; i + 1 < n; ++i)
      if (rng() % 4 != 0) link(i, i + 1);                              // chains
    for (std::size_t k = 0; k < n / 2; ++k) link(any(rng), any(rng));  // and shortcuts
    std::vector<char> keep(n);
    for (char& k : keep) k = rng() % 8 != 0;
    // Expected: breadth-first search from each smallest unvisited kept id.
    const auto components_by_search = [&](const std::vector<char>& kept) {
      std::vector<std::uint32_t> expected(n, UINT32_MAX);
      for (std::size_t s = 0; s < n; ++s) {
        if (!kept[s] || expected[s] != UINT32_MAX) continue;
        std::vector<std::size_t> queue{s};
        expected[s] = static_cast<std::uint32_t>(s);
        for (std::size_t q = 0; q < queue.size(); ++q)
          for (const std::uint32_t j : grid.neighbors[queue[q]])
            if (j != core::kNoNeighbor && kept[j] && expected[j] == UINT32_MAX) {
              expected[j] = static_cast<std::uint32_t>(s);
              queue.push_back(j);
            }
      }
      return expected;
    };
    const std::vector<std::uint32_t> expected = components_by_search(keep);
    // An operand's range of ids (the proof's form): the middle half.
    const std::size_t first = n / 4, count = n - n / 2;
    std::vector<char> in_range(n, 0);
    std::fill(in_range.begin() + static_cast<std::ptrdiff_t>(first),
              in_range.begin() + static_cast<std::ptrdiff_t>(first + count), 1);
    const std::vector<std::uint32_t> expected_range = components_by_search(in_range);
    for (const int threads : {1, 2, 4, 8}) {
      core::FillVector<std::uint32_t> got, got_range;
      tbb::task_arena(threads).execute([&] {
        got = core::neighbour_components(grid, keep);
        got_range = core::neighbour_components(grid, static_cast<std::uint32_t>(first), count);
      });
      ASSERT_EQ(got.size(), n);
      for (std::size_t i = 0; i < n; ++i) {
        if (keep[i]) {
          ASSERT_EQ(got[i], expected[i]) << "n " << n << ", triangle " << i << ", threads " << threads;
        }
      }
      ASSERT_EQ(got_range.size(), count);
      for (std::size_t i = 0; i < count; ++i)
        ASSERT_EQ(got_range[i], expected_range[first + i])
            << "n " << n << ", triangle " << first + i << ", threads " << threads;
    }
  }
}

}  // namespace
}  // namespace ember::test
