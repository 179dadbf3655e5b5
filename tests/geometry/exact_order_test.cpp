// Order, identity and projected orientation of computed points
// (ember/geometry/exact_order.hpp) against GMP rationals. Random points are
// almost always decided by the double filter, so the tests also (a) build the
// cases the filter cannot decide -- one point from different plane triples
// (different homogeneous scales), collinear computed points, points a tiny
// fraction of an ulp apart -- and count, by mirroring the filter's acceptance
// test, that the exact wide-integer branch really decided them, and (b) run
// the exact branch alone on random points by blanking the cached doubles.
#include <gtest/gtest.h>

#include <algorithm>
#include <optional>
#include <utility>
#include <vector>

#include "geometry/exact_order.hpp"
#include "support/geometry_oracle.hpp"

namespace ember::test {
namespace {

using Rat3 = std::array<mpq_class, 3>;

Rat3 rational(const Point& p) {
  const MpPoint o = to_mp(p);
  Rat3 r{mpq_class(o[0], o[3]), mpq_class(o[1], o[3]), mpq_class(o[2], o[3])};
  for (mpq_class& c : r) c.canonicalize();
  return r;
}
int sign_q(const mpq_class& v) { return v > 0 ? 1 : (v < 0 ? -1 : 0); }
int cmp_q(const mpq_class& a, const mpq_class& b) { return a == b ? 0 : (a < b ? -1 : 1); }
int oracle_lex(const Rat3& a, const Rat3& b) {
  for (int k = 0; k < 3; ++k)
    if (const int c = cmp_q(a[k], b[k])) return c;
  return 0;
}
/// 2D orientation of the rational points projected to (drop+1, drop+2) mod 3.
int oracle_orient(const Rat3& a, const Rat3& b, const Rat3& c, int drop) {
  const int u = (drop + 1) % 3, v = (drop + 2) % 3;
  return sign_q((b[u] - a[u]) * (c[v] - a[v]) - (b[v] - a[v]) * (c[u] - a[u]));
}

// Mirrors of the filters' acceptance tests in exact_order.hpp: false means the
// exact branch must have produced the answer.
bool coord_filter_decides(const Point& a, const Point& b, int axis) {
  const double fa = a.f[axis], fb = b.f[axis];
  return std::fabs(fa - fb) > 32 * 0x1p-53 * (std::fabs(fa) + std::fabs(fb));
}
bool orient_filter_decides(const Point& a, const Point& b, const Point& c, int drop) {
  const int u = (drop + 1) % 3, v = (drop + 2) % 3;
  const double det = (b.f[u] - a.f[u]) * (c.f[v] - a.f[v]) - (b.f[v] - a.f[v]) * (c.f[u] - a.f[u]);
  double m = 0;
  for (const Point* p : {&a, &b, &c}) m = std::max({m, std::fabs(p->f[u]), std::fabs(p->f[v])});
  return std::fabs(det) > 256 * 0x1p-53 * m * m;
}
/// A copy whose cached doubles are all 0: both filters then see a zero
/// difference / determinant with a zero bound and always fall through to the
/// exact branch, which is thereby tested on full-width random data.
Point blind(Point p) {
  p.f = {0, 0, 0};
  return p;
}
/// The parallel plane with offset d + delta.
Plane shifted(Plane p, int delta) {
  p.d = OffsetCoef::assume_bound(p.d + OffsetCoef(delta));
  return p;
}
std::int64_t& at(IntPoint& p, int k) { return k == 0 ? p.x : (k == 1 ? p.y : p.z); }

/// "G" is a grid point through to_point; "C" is SSS with every triangle vertex
/// at a corner of the [-2^25, 2^25]^3 cube (the largest normals and offsets,
/// hence the widest products); the others are plane kinds for intersect.
const char* const kKinds[] = {"SSS", "SSE", "SEA", "AAA", "G", "C"};
constexpr int kNumKinds = 6;

Point random_point(Gen& g, const char* kinds) {
  if (kinds[0] == 'G') return to_point(g.point());
  if (kinds[0] == 'C') {
    auto corner = [&] { return (g.rng()() & 1) ? kCoordLimit : -kCoordLimit; };
    auto vertex = [&] { return IntPoint{corner(), corner(), corner()}; };
    auto plane = [&] {
      for (;;)
        if (const auto s = supporting_plane(vertex(), vertex(), vertex())) return *s;
    };
    for (;;)
      if (const auto x = intersect(plane(), plane(), plane())) return *x;
  }
  for (;;) {
    Plane pl[3] = {g.plane(kinds[0]), g.plane(kinds[1]), g.plane(kinds[2])};
    std::rotate(pl, pl + g.uniform(0, 2), pl + 3);
    if (const auto x = intersect(pl[0], pl[1], pl[2])) return *x;
  }
}

/// Planes through the line p0 p1 of two grid points: the supporting planes of
/// two triangles on that edge, their edge planes, and for an axis-parallel
/// line the two axis planes containing it. Any two non-parallel members cut
/// out the same line, so a third plane gives the same point from several
/// triples with unrelated homogeneous scales.
struct Line {
  std::vector<Plane> planes;
  std::vector<std::pair<int, int>> pairs;  // non-parallel members
  /// The point where the line meets x, once per pair (empty if x is parallel to the line).
  std::vector<Point> meet(const Plane& x) const {
    std::vector<Point> r;
    for (const auto& [i, j] : pairs)
      if (const auto p = intersect(planes[i], planes[j], x)) r.push_back(*p);
    return r;
  }
};

/// parallel_axis < 0: a general line; else a line parallel to that axis.
std::optional<Line> make_line(Gen& g, int parallel_axis) {
  IntPoint p0 = g.point(), p1 = g.point();
  const IntPoint p2 = g.point(), p3 = g.point();
  if (parallel_axis >= 0) {
    p1 = p0;
    at(p1, parallel_axis) = g.coord();
  }
  if (p0 == p1) return std::nullopt;
  const auto s = supporting_plane(p0, p1, p2), t = supporting_plane(p1, p0, p3);
  if (!s || !t || parallel(*s, *t)) return std::nullopt;
  Line l;
  l.planes = {*s, *t, edge_plane(p0, p1, *s), edge_plane(p1, p0, *t)};
  for (int k = 0; parallel_axis >= 0 && k < 3; ++k)
    if (k != parallel_axis) l.planes.push_back(axis_plane(k, at(p0, k)));
  for (int i = 0; i < static_cast<int>(l.planes.size()); ++i)
    for (int j = i + 1; j < static_cast<int>(l.planes.size()); ++j)
      if (!parallel(l.planes[i], l.planes[j])) l.pairs.emplace_back(i, j);
  return l;
}

TEST(ExactOrder, CompareCoordMatchesOracleOnRandomPoints) {
  // Random pairs over every combination of kinds, coordinates clustered at
  // +-2^25: filtered and exact-only (blind) results against the rational sign.
  Gen g(501);
  int max_bits = 0;
  for (int i = 0; i < 5000; ++i) {
    const char *ka = kKinds[i % kNumKinds], *kb = kKinds[(i / kNumKinds) % kNumKinds];
    const Point a = random_point(g, ka), b = random_point(g, kb);
    const Rat3 qa = rational(a), qb = rational(b);
    const MpPoint ma = to_mp(a), mb = to_mp(b);
    for (int axis = 0; axis < 3; ++axis) {
      const int expected = cmp_q(qa[axis], qb[axis]);
      EXPECT_EQ(compare_coord(a, b, axis), expected) << ka << " " << kb << " axis " << axis;
      EXPECT_EQ(compare_coord(b, a, axis), -expected) << ka << " " << kb;
      EXPECT_EQ(compare_coord(blind(a), blind(b), axis), expected) << ka << " " << kb;
      max_bits = std::max(max_bits, bits_of(ma[axis] * mb[3] - mb[axis] * ma[3]));
    }
    EXPECT_EQ(same_point(a, b), qa == qb);
  }
  // Attainable magnitudes stay a few bits below the type bound (|n| <= sqrt(3)
  // 2^52 caps w near 2^159), but they must reach the top limb of the storage.
  EXPECT_LE(max_bits, CrossCoord::bits);
  EXPECT_GT(max_bits, 64 * (CrossCoord::limbs - 1));
}

TEST(ExactOrder, SamePointAcrossPlaneTriplesAndSubUlpNeighbours) {
  // The meeting point of a line and a plane, built from every pair of planes
  // through the line: identical points at different scales (the filter sees
  // equal doubles and must defer). Shifting the third plane's offset by 1
  // moves the point by ~2^-52 at coordinates ~2^25: far below an ulp. On an
  // axis-parallel line the shift changes that one coordinate only.
  Gen g(502);
  int equal_pairs = 0, scaled = 0, sub_ulp = 0, exact_nonzero = 0;
  for (int i = 0; i < 1500; ++i) {
    const int axis = i % 4 - 1;
    const auto line = make_line(g, axis);
    if (!line) continue;
    const Plane x = g.plane("SE"[i % 2]);
    const std::vector<Point> pts = line->meet(x);
    if (pts.empty()) continue;
    const Rat3 q0 = rational(pts[0]);
    for (const Point& p : pts) {
      ASSERT_EQ(rational(p), q0);  // the construction, checked by the oracle
      EXPECT_TRUE(same_point(pts[0], p));
      EXPECT_TRUE(same_point(p, pts[0]));
      EXPECT_EQ(compare_lex(pts[0], p), 0);
      for (int k = 0; k < 3; ++k) EXPECT_EQ(compare_coord(p, pts[0], k), 0);
      ++equal_pairs;
      scaled += to_mp(p)[3] != to_mp(pts[0])[3];
    }
    for (const int delta : {-1, 1}) {
      const std::vector<Point> near = line->meet(shifted(x, delta));
      for (std::size_t j = 0; j < near.size(); ++j) {
        const Point &a = pts[j % pts.size()], &b = near[j];
        const Rat3 qb = rational(b);
        ASSERT_NE(qb, q0);
        EXPECT_FALSE(same_point(a, b));
        EXPECT_EQ(compare_lex(a, b), oracle_lex(q0, qb));
        for (int k = 0; k < 3; ++k) {
          const int expected = cmp_q(q0[k], qb[k]);
          EXPECT_EQ(compare_coord(a, b, k), expected) << "line axis " << axis << " coord " << k;
          EXPECT_EQ(compare_coord(b, a, k), -expected);
          if (axis >= 0 && k != axis) {
            EXPECT_EQ(expected, 0);  // only one coordinate moves
          }
          if (expected != 0 && !coord_filter_decides(a, b, k)) ++exact_nonzero;
          const mpq_class gap = abs(q0[k] - qb[k]);
          if (expected != 0 && gap * pow2(52) < abs(q0[k])) ++sub_ulp;
        }
      }
    }
  }
  // Grid vertices: to_point, +-axis planes (AAA, w = 1) and three supporting
  // planes of triangles sharing the vertex (SSS, w up to ~2^158) are one point; one
  // of those planes shifted by 1 gives a point a sub-ulp distance away.
  for (int i = 0; i < 1000; ++i) {
    const IntPoint v = g.point();
    const Point grid = to_point(v);
    const auto aaa = intersect(axis_plane(1, v.y), -axis_plane(2, v.z), axis_plane(0, v.x));
    const auto t1 = supporting_plane(v, g.point(), g.point()), t2 = supporting_plane(g.point(), v, g.point()),
               t3 = supporting_plane(g.point(), g.point(), v);
    ASSERT_TRUE(aaa);
    EXPECT_TRUE(same_point(grid, *aaa));
    if (!t1 || !t2 || !t3) continue;
    const auto sss = intersect(*t1, *t2, *t3), off = intersect(*t1, *t2, shifted(*t3, 1));
    if (!sss) continue;
    ASSERT_EQ(rational(*sss), rational(grid));
    EXPECT_TRUE(same_point(*sss, grid));
    EXPECT_TRUE(same_point(*aaa, *sss));
    EXPECT_EQ(compare_lex(*sss, *aaa), 0);
    ++equal_pairs;
    const Rat3 qo = rational(*off);
    EXPECT_FALSE(same_point(*off, grid));
    EXPECT_EQ(compare_lex(*off, *sss), oracle_lex(qo, rational(grid)));
    for (int k = 0; k < 3; ++k) exact_nonzero += qo[k] != rational(grid)[k] && !coord_filter_decides(*off, *sss, k);
  }
  EXPECT_GT(equal_pairs, 10000);
  EXPECT_GT(scaled, 8000);  // equal points really stored at different scales
  EXPECT_GT(sub_ulp, 15000);
  EXPECT_GT(exact_nonzero, 25000);  // nonzero answers that only the exact branch could give
}

TEST(ExactOrder, EqualWeightPointsCompareByNumerators) {
  // compare_coord and same_point answer points with the same w from the
  // numerators alone. Neighbours that differ by one unit in one numerator
  // (a step of 1/w, far below an ulp when w is large) and the point itself.
  Gen g(503);
  int sub_ulp = 0;
  for (int i = 0; i < 3000; ++i) {
    const Point a = random_point(g, kKinds[i % kNumKinds]);
    const int axis = i % 3;
    for (const int delta : {-1, 0, 1}) {
      Point b = a;
      PointXYZ& c = axis == 0 ? b.x : (axis == 1 ? b.y : b.z);
      c = PointXYZ::assume_bound(c + Int<64>(delta));  // attainable points stay well below 2^188
      detail::cache_approx(b);
      const Rat3 qa = rational(a), qb = rational(b);
      EXPECT_EQ(same_point(a, b), qa == qb);
      EXPECT_EQ(same_point(blind(a), blind(b)), qa == qb);
      for (int k = 0; k < 3; ++k) {
        EXPECT_EQ(compare_coord(a, b, k), cmp_q(qa[k], qb[k]));
        EXPECT_EQ(compare_coord(blind(b), blind(a), k), cmp_q(qb[k], qa[k]));
      }
      EXPECT_EQ(compare_lex(a, b), oracle_lex(qa, qb));
      sub_ulp += delta != 0 && !coord_filter_decides(a, b, axis);
    }
  }
  EXPECT_GT(sub_ulp, 1000);  // most steps are decided by the numerators, not the filter
}

TEST(ExactOrder, AsGridPointRecognizesExactlyTheIntegerPoints) {
  // Grid points built as the meeting point of three supporting planes through
  // them (w up to ~2^158), random computed points (almost never integral),
  // and each grid point moved by a sub-ulp step (one plane shifted by 1).
  Gen g(504);
  int grid_found = 0, rejected = 0;
  auto check = [&](const Point& p) {
    const Rat3 q = rational(p);
    const mpq_class limit(static_cast<long>(kCoordLimit));
    const bool in_range = abs(q[0]) <= limit && abs(q[1]) <= limit && abs(q[2]) <= limit;
    const bool integral = q[0].get_den() == 1 && q[1].get_den() == 1 && q[2].get_den() == 1;
    const std::optional<IntPoint> r = as_grid_point(p);
    ASSERT_EQ(r.has_value(), integral && in_range) << q[0] << " " << q[1] << " " << q[2];
    if (r) {
      EXPECT_EQ(mpq_class(static_cast<long>(r->x)), q[0]);
      EXPECT_EQ(mpq_class(static_cast<long>(r->y)), q[1]);
      EXPECT_EQ(mpq_class(static_cast<long>(r->z)), q[2]);
      ++grid_found;
    } else {
      ++rejected;
    }
  };
  for (int i = 0; i < 2000; ++i) {
    check(random_point(g, kKinds[i % kNumKinds]));
    const IntPoint v = g.point();
    const auto t1 = supporting_plane(v, g.point(), g.point()), t2 = supporting_plane(g.point(), v, g.point()),
               t3 = supporting_plane(g.point(), g.point(), v);
    if (!t1 || !t2 || !t3) continue;
    if (const auto sss = intersect(*t1, *t2, *t3)) check(*sss);
    if (const auto off = intersect(*t1, *t2, shifted(*t3, 1))) check(*off);
  }
  // w = 1 takes a fast path (the numerators are the coordinates): the range
  // limits and numerators past int64 must still be rejected.
  const auto w_one = [](const PointXYZ& x, const PointXYZ& y, const PointXYZ& z) {
    Point p{x, y, z, PointW(1), {}};
    detail::cache_approx(p);
    return p;
  };
  const PointXYZ big = PointXYZ::assume_bound(PointXYZ(1) * Int<64>(std::int64_t{1} << 62) * Int<64>(8));  // 2^65
  for (const std::int64_t edge : {kCoordLimit, -kCoordLimit, kCoordLimit + 1, -kCoordLimit - 1, std::int64_t{0}}) {
    check(w_one(PointXYZ(edge), PointXYZ(3), PointXYZ(-edge / 2)));
    check(w_one(PointXYZ(1), PointXYZ(edge), PointXYZ(2)));
  }
  check(w_one(big, PointXYZ(0), PointXYZ(0)));
  check(w_one(PointXYZ(0), -big, PointXYZ(0)));
  check(w_one(PointXYZ(0), PointXYZ(0), PointXYZ::assume_bound(big + Int<64>(5))));
  EXPECT_GT(grid_found, 2000);  // the SSS grid points and the "G" kind
  EXPECT_GT(rejected, 2000);
}

TEST(ExactOrder, Orient2dDroppedMatchesOracleOnRandomTriples) {
  // Every drop axis, every permutation (cyclic: same sign, transposition:
  // opposite), filtered and exact-only; repeated points are collinear.
  Gen g(503);
  int max_bits = 0;
  for (int i = 0; i < 3000; ++i) {
    const Point p[3] = {random_point(g, kKinds[i % kNumKinds]), random_point(g, kKinds[(i / kNumKinds) % kNumKinds]),
                        random_point(g, kKinds[(i / (kNumKinds * kNumKinds)) % kNumKinds])};
    const Rat3 q[3] = {rational(p[0]), rational(p[1]), rational(p[2])};
    const MpPoint m[3] = {to_mp(p[0]), to_mp(p[1]), to_mp(p[2])};
    for (int drop = 0; drop < 3; ++drop) {
      const int o = oracle_orient(q[0], q[1], q[2], drop);
      for (const auto& [a, b, c, s] : {std::array{0, 1, 2, 1}, std::array{1, 2, 0, 1}, std::array{2, 0, 1, 1},
                                       std::array{1, 0, 2, -1}, std::array{0, 2, 1, -1}, std::array{2, 1, 0, -1}})
        EXPECT_EQ(orient2d_dropped(p[a], p[b], p[c], drop), s * o) << "drop " << drop << " case " << i;
      EXPECT_EQ(orient2d_dropped(blind(p[0]), blind(p[1]), blind(p[2]), drop), o) << "drop " << drop;
      EXPECT_EQ(orient2d_dropped(p[0], p[0], p[2], drop), 0);
      EXPECT_EQ(orient2d_dropped(blind(p[1]), blind(p[2]), blind(p[1]), drop), 0);
      // Width of the homogeneous det [a_u a_v a_w; b_u b_v b_w; c_u c_v c_w] the exact branch evaluates.
      const int u = (drop + 1) % 3, v = (drop + 2) % 3;
      max_bits = std::max(
          max_bits, bits_of(det3(m[0][u], m[0][v], m[0][3], m[1][u], m[1][v], m[1][3], m[2][u], m[2][v], m[2][3])));
    }
  }
  EXPECT_LE(max_bits, Orient2Value::bits);
  EXPECT_GT(max_bits, 64 * (Orient2Value::limbs - 1));  // top limb in use (see the compare test)
}

TEST(ExactOrder, Orient2dDroppedOnCollinearAndNearlyCollinearPoints) {
  // Three points of one line from different plane pairs and third planes are
  // collinear in every projection; replacing a plane of the third point's pair
  // by its offset +-1 moves it off the line by ~2^-52: the determinant is then
  // far below the filter bound and only the exact branch can give its sign.
  Gen g(504);
  int collinear = 0, exact_nonzero = 0;
  for (int i = 0; i < 1500; ++i) {
    const auto line = make_line(g, i % 4 - 1);
    if (!line) continue;
    const std::vector<Point> a = line->meet(g.plane('S')), b = line->meet(g.plane("SEA"[i % 3]));
    if (a.empty() || b.empty()) continue;
    const Plane x = g.plane('S');
    const auto [pi, pj] = line->pairs[i % line->pairs.size()];
    const auto on = intersect(line->planes[pi], line->planes[pj], x);
    const auto off = intersect(line->planes[pi], shifted(line->planes[pj], i % 2 ? 1 : -1), x);
    if (!on || !off) continue;
    const Point& pa = a[i % a.size()];
    const Point& pb = b[(i / 3) % b.size()];
    const Rat3 qa = rational(pa), qb = rational(pb), qoff = rational(*off);
    for (int drop = 0; drop < 3; ++drop) {
      ASSERT_EQ(oracle_orient(qa, qb, rational(*on), drop), 0);
      EXPECT_EQ(orient2d_dropped(pa, pb, *on, drop), 0);
      EXPECT_EQ(orient2d_dropped(*on, pa, pb, drop), 0);
      EXPECT_EQ(orient2d_dropped(pb, pa, *on, drop), 0);
      EXPECT_EQ(orient2d_dropped(pa, a[0], *on, drop), 0);  // pa, a[0]: one point, two scales
      ++collinear;
      const int o = oracle_orient(qa, qb, qoff, drop);
      EXPECT_EQ(orient2d_dropped(pa, pb, *off, drop), o) << "drop " << drop << " case " << i;
      EXPECT_EQ(orient2d_dropped(pb, *off, pa, drop), o);
      EXPECT_EQ(orient2d_dropped(pb, pa, *off, drop), -o);
      EXPECT_EQ(orient2d_dropped(*off, pb, pa, drop), -o);
      if (o != 0 && !orient_filter_decides(pa, pb, *off, drop)) ++exact_nonzero;
    }
  }
  EXPECT_GT(collinear, 2500);
  EXPECT_GT(exact_nonzero, 1200);
}

TEST(ExactOrder, CompareLexIsConsistentTotalOrder) {
  // A pool with exact ties: random points of every kind (grid points share
  // the +-2^25 corner coordinates), one line point at several scales and its
  // sub-ulp neighbours, points on axis-parallel lines (equal in two coordinates).
  Gen g(505);
  std::vector<Point> pool;
  for (int i = 0; i < 240; ++i) pool.push_back(random_point(g, kKinds[i % kNumKinds]));
  for (int i = 0; pool.size() < 460; ++i) {
    const auto line = make_line(g, i % 4 - 1);
    if (!line) continue;
    const Plane x = g.plane("SE"[i % 2]);
    for (const Plane& y : {x, shifted(x, 1), shifted(x, -1)}) {
      const std::vector<Point> pts = line->meet(y);
      pool.insert(pool.end(), pts.begin(), pts.begin() + std::min<std::size_t>(pts.size(), 2));
    }
  }
  std::vector<Rat3> q;
  for (const Point& p : pool) q.push_back(rational(p));
  int ties = 0;
  for (std::size_t i = 0; i < pool.size(); ++i)
    for (std::size_t j = 0; j < pool.size(); ++j) {
      const int c = compare_lex(pool[i], pool[j]);
      ASSERT_EQ(c, oracle_lex(q[i], q[j])) << i << " " << j;
      EXPECT_EQ(compare_lex(pool[j], pool[i]), -c);
      EXPECT_EQ(c == 0, same_point(pool[i], pool[j]));
      ties += c == 0 && i != j;
    }
  EXPECT_GT(ties, 300);
  // Sorting by compare_lex yields the oracle's order (transitivity in practice).
  std::vector<std::size_t> idx(pool.size());
  for (std::size_t i = 0; i < idx.size(); ++i) idx[i] = i;
  std::sort(idx.begin(), idx.end(), [&](std::size_t a, std::size_t b) { return compare_lex(pool[a], pool[b]) < 0; });
  for (std::size_t i = 1; i < idx.size(); ++i) EXPECT_LE(oracle_lex(q[idx[i - 1]], q[idx[i]]), 0);
}

}  // namespace
}  // namespace ember::test
