// Chord constraints and the two floating-point chord filters of chords.hpp.
#include "core/route/shared/chords.hpp"

#include <algorithm>
#include <array>
#include <cmath>

namespace ember::core {

void chord_constraints(const Polygon& poly, const std::vector<std::int8_t>& signs, std::vector<Plane>& out) {
  const std::size_t n = poly.edges.size();
  for (std::size_t i = 0; i < n; ++i) {
    const int a = signs[i], b = signs[(i + 1) % n];  // edge i runs from vertex i to i+1
    if (a == 0 || b == 0 || a != b) out.push_back(poly.edges[i]);
  }
}

namespace {

// Error budget. A vertex approximation f is within 8 ulp of the exact
// coordinate (point.hpp), so |f - x| <= 2^-49 |f| per coordinate. The filter
// only runs while every |f| <= 2^30 (the grid is 2^26 wide, so always in
// practice) and |d| = 1 (|d|_1 <= sqrt 3):
//  * a projection d . f is within 2^-44 M of d . x (2 * 2^-49 M * sqrt 3 for
//    the vertex error, < 2^-50 * 4 M for the three roundings), M = max |f|;
//  * a plane value n . f + n_d is within delta = 2^-44 (|n_a f_x| + |n_b f_y|
//    + |n_c f_z| + |n_d|) of the exact one: the vertex error contributes
//    2^-49 of each term, n_d's conversion 2^-52 (int.hpp; n_a, n_b, n_c are
//    exact, < 2^53), four roundings 2^-51 of the sum of the terms;
//  * the interval arithmetic below rounds a few more times, each by at most
//    2^-52 of values below 2^32: < 2^-18, far below the margin kMargin.
constexpr double kVertexSlack = 0x1p-44;
constexpr double kPlaneSlack = 0x1p-44;
constexpr double kMaxCoord = 0x1p30;
constexpr double kMargin = 0x1p-12;

struct PlaneDoubles {
  double a, b, c, d;
  explicit PlaneDoubles(const Plane& p)
      : a(static_cast<double>(p.a.raw())),
        b(static_cast<double>(p.b.raw())),
        c(static_cast<double>(p.c.raw())),
        d(p.d.to_double()) {}
  double value(const std::array<double, 3>& f) const { return a * f[0] + b * f[1] + c * f[2] + d; }
  double slack(const std::array<double, 3>& f) const {
    return kPlaneSlack * (std::fabs(a * f[0]) + std::fabs(b * f[1]) + std::fabs(c * f[2]) + std::fabs(d));
  }
};

/// The common line's direction na x nb, normalized; false when the planes
/// are (nearly) parallel in double. Any direction separates disjoint
/// intervals of one line; this one separates best.
bool common_direction(const PlaneDoubles& pa, const PlaneDoubles& pb, std::array<double, 3>& d) {
  d = {pa.b * pb.c - pa.c * pb.b, pa.c * pb.a - pa.a * pb.c, pa.a * pb.b - pa.b * pb.a};
  const double len = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
  if (!(len > 0) || !std::isfinite(len)) return false;
  for (double& x : d) x /= len;
  return true;
}

/// Double estimate of the interval that a convex polygon's chord along
/// `plane` covers on the direction `d`, from the cached vertex
/// approximations and the vertices' exact signs against the plane.
std::array<double, 2> approx_chord(const Polygon& poly, const std::vector<std::int8_t>& signs,
                                   const PlaneDoubles& plane, const std::array<double, 3>& d) {
  std::array<double, 2> range{HUGE_VAL, -HUGE_VAL};
  const auto add = [&](const std::array<double, 3>& x) {
    const double t = d[0] * x[0] + d[1] * x[1] + d[2] * x[2];
    range[0] = std::min(range[0], t);
    range[1] = std::max(range[1], t);
  };
  const std::size_t n = poly.vertices.size();
  for (std::size_t i = 0; i < n; ++i) {
    const std::size_t j = i + 1 == n ? 0 : i + 1;
    const auto& fi = poly.vertices[i].f;
    if (signs[i] == 0) add(fi);
    if (signs[i] * signs[j] >= 0) continue;
    const auto& fj = poly.vertices[j].f;
    const double di = plane.value(fi), dj = plane.value(fj);
    const double t = di / (di - dj);
    add({fi[0] + t * (fj[0] - fi[0]), fi[1] + t * (fj[1] - fi[1]), fi[2] + t * (fj[2] - fi[2])});
  }
  return range;
}

/// Rigorous bounds on d . x over the chord where `plane` crosses the convex
/// polygon. A chord point is a vertex on the plane or the crossing X of an
/// edge (v_i, v_j) whose ends lie strictly on opposite sides: X = v_i +
/// tau (v_j - v_i) with tau = A_i / (A_i + A_j), A = |exact plane value|,
/// which grows with A_i and shrinks with A_j; the approximate plane values
/// bound A_i and A_j, hence tau, hence d . X. False if a coordinate is out of
/// the budget's range.
bool chord_bounds(const Polygon& poly, const std::vector<std::int8_t>& signs, const PlaneDoubles& plane,
                  const std::array<double, 3>& d, std::array<double, 2>& range) {
  range = {HUGE_VAL, -HUGE_VAL};
  const std::size_t n = poly.vertices.size();
  for (std::size_t i = 0; i < n; ++i) {
    const std::array<double, 3>& fi = poly.vertices[i].f;
    const double mi = std::max({std::fabs(fi[0]), std::fabs(fi[1]), std::fabs(fi[2])});
    if (!(mi <= kMaxCoord)) return false;
    const std::size_t j = i + 1 == n ? 0 : i + 1;
    const double pi = d[0] * fi[0] + d[1] * fi[1] + d[2] * fi[2];
    if (signs[i] == 0) {
      range[0] = std::min(range[0], pi - kVertexSlack * mi);
      range[1] = std::max(range[1], pi + kVertexSlack * mi);
    }
    if (signs[i] * signs[j] >= 0) continue;
    const std::array<double, 3>& fj = poly.vertices[j].f;
    const double mj = std::max({std::fabs(fj[0]), std::fabs(fj[1]), std::fabs(fj[2])});
    if (!(mj <= kMaxCoord)) return false;
    const double pj = d[0] * fj[0] + d[1] * fj[1] + d[2] * fj[2];
    // |exact value| of each end, from its sign and the approximation.
    const double ai = signs[i] * plane.value(fi), si = plane.slack(fi);
    const double aj = signs[j] * plane.value(fj), sj = plane.slack(fj);
    const double ai_lo = std::max(0.0, ai - si), ai_hi = ai + si;
    const double aj_lo = std::max(0.0, aj - sj), aj_hi = aj + sj;
    if (!(ai_hi > 0) || !(aj_hi > 0)) return false;  // nothing known: no bound
    const double tau_lo = ai_lo / (ai_lo + aj_hi), tau_hi = ai_hi / (ai_hi + aj_lo);
    const double x0 = pi + tau_lo * (pj - pi), x1 = pi + std::min(1.0, tau_hi) * (pj - pi);
    const double slack = kVertexSlack * std::max(mi, mj);
    range[0] = std::min({range[0], x0 - slack, x1 - slack});
    range[1] = std::max({range[1], x0 + slack, x1 + slack});
  }
  return range[0] <= range[1];
}

}  // namespace

namespace {

bool surely_disjoint_along(const Polygon& a, const PlaneDoubles& pa, const std::vector<std::int8_t>& signs_a,
                           const Polygon& b, const PlaneDoubles& pb, const std::vector<std::int8_t>& signs_b,
                           const std::array<double, 3>& d) {
  std::array<double, 2> p, q;
  if (!chord_bounds(a, signs_a, pb, d, p) || !chord_bounds(b, signs_b, pa, d, q)) return false;
  return p[1] + kMargin < q[0] || q[1] + kMargin < p[0];
}

}  // namespace

bool chords_surely_disjoint(const Polygon& a, const Plane& sa, const std::vector<std::int8_t>& signs_a,
                            const Polygon& b, const Plane& sb, const std::vector<std::int8_t>& signs_b) {
  const PlaneDoubles pa(sa), pb(sb);
  std::array<double, 3> d;
  return common_direction(pa, pb, d) && surely_disjoint_along(a, pa, signs_a, b, pb, signs_b, d);
}

ChordOverlap filter_chords(const Polygon& a, const Plane& sa, const std::vector<std::int8_t>& signs_a, const Polygon& b,
                           const Plane& sb, const std::vector<std::int8_t>& signs_b) {
  const PlaneDoubles pa(sa), pb(sb);
  std::array<double, 3> d;
  if (!common_direction(pa, pb, d)) return ChordOverlap::kUnsure;
  const auto p = approx_chord(a, signs_a, pb, d);
  const auto q = approx_chord(b, signs_b, pa, d);
  if (std::min(p[1], q[1]) - std::max(p[0], q[0]) > 0x1p-10) return ChordOverlap::kYes;
  // Most pairs that get here do not meet at all, which the rigorous bounds
  // can tell (7x cheaper than the exact test); chords that touch or nearly
  // do stay unsure.
  return surely_disjoint_along(a, pa, signs_a, b, pb, signs_b, d) ? ChordOverlap::kNo : ChordOverlap::kUnsure;
}

bool chords_separated_by_edge(const Polygon& a, const Polygon& b) {
  // a lies in {E <= 0} and b in {E >= 0}, so the chords, both on the line
  // L = sa ∩ sb, share only points of E. L is not in E: E meets sa in the
  // line of a's edge, and a with vertices strictly on both sides of sb is on
  // both sides of L in sa. So L meets E in at most one point.
  for (const Plane& e : a.edges) {
    const auto beyond = [&](const Point& v) { return classify(v, e) >= 0; };
    if (std::all_of(b.vertices.begin(), b.vertices.end(), beyond)) return true;
  }
  return false;
}

}  // namespace ember::core
