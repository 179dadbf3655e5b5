#pragma once
// Exact predicates on computed (homogeneous) points that the Boolean core never
// needs but the mesh output does: coordinate order, identity, and orientation
// of three points in a plane. They go past the core's 256-bit budget
// (numbers/int.hpp: kWideMaxBits), so each runs behind a floating-point filter
// on the points' cached doubles and falls back to exact wide integers only
// when the filter cannot decide.
//
// Filter bounds (u = 2^-53): Point::f holds x/w with relative error < 8u.
//  * compare: |f_a - f_b| > 32u (|f_a| + |f_b|) cannot change sign by errors of
//    at most 8u|x_a| + 8u|x_b| plus one rounding of the difference.
//  * orient: with M the largest |coordinate| involved, every difference errs by
//    < 18uM, every product by < 80uM^2, the determinant by < 170uM^2; the
//    filter accepts |det| > 256uM^2.
#include <algorithm>
#include <array>
#include <cmath>
#include <optional>

#include "geometry/point.hpp"

namespace ember {

/// x1..x3 times w of another point: 188 + 162 = 350 bits, difference 351.
using CrossCoord = Int<351>;
static_assert(std::is_same_v<decltype(PointXYZ{} * PointW{} - PointXYZ{} * PointW{}), CrossCoord>,
              "coordinate comparison: 188 + 162 = 350, difference -> 351");

/// 2D minor of two projected points: 188 + 188 = 376, difference 377.
using ProjectedMinor = Int<377>;
/// Homogeneous 2D orientation: w (162) times a minor (377) = 539, three terms -> 541.
using Orient2Value = Int<541>;
static_assert(
    std::is_same_v<decltype(PointW{} * ProjectedMinor{} - PointW{} * ProjectedMinor{} + PointW{} * ProjectedMinor{}),
                   Orient2Value>,
    "projected orientation: 162 + 377 = 539, three terms -> 541");
static_assert(Orient2Value::bits <= kWideMaxBits, "orientation must fit the wide storage limit");

namespace detail {
inline const PointXYZ& coord(const Point& p, int axis) { return axis == 0 ? p.x : (axis == 1 ? p.y : p.z); }
}  // namespace detail

/// Sign of a_axis - b_axis (Cartesian coordinates), exact.
inline int compare_coord(const Point& a, const Point& b, int axis) {
  const double fa = a.f[axis], fb = b.f[axis];
  const double bound = 32 * 0x1p-53 * (std::fabs(fa) + std::fabs(fb));
  if (fa - fb > bound) return 1;
  if (fb - fa > bound) return -1;
  // Equal w (most often both 1, or one point computed twice alike): compare numerators.
  if (a.w == b.w) {
    const PointXYZ &xa = detail::coord(a, axis), &xb = detail::coord(b, axis);
    return xa == xb ? 0 : (xa < xb ? -1 : 1);
  }
  // w > 0 for both, so the sign of x_a/w_a - x_b/w_b is that of x_a w_b - x_b w_a.
  const CrossCoord v = detail::coord(a, axis) * b.w - detail::coord(b, axis) * a.w;
  return v.sign();
}

/// The two points are the same point (exact; representations may differ in scale).
inline bool same_point(const Point& a, const Point& b) {
  if (a.w == b.w) return a.x == b.x && a.y == b.y && a.z == b.z;  // w > 0: equal ratios iff equal numerators
  return compare_coord(a, b, 0) == 0 && compare_coord(a, b, 1) == 0 && compare_coord(a, b, 2) == 0;
}

/// The grid point that p is, if its three coordinates are integers within the
/// grid's range (|x| <= kCoordLimit; every output vertex is). The
/// candidate is the cached double rounded to the nearest integer (f is within
/// 8 ulp of x/w, and 8 ulp at |x/w| <= 2^25 is at most 2^-25, so an integer
/// x/w is found, and f farther than 2^-20 from every integer rules it out),
/// then confirmed exactly: g w == x (26 + 162 bits, inside PointXYZ's 188).
/// Never wrong: a candidate that fails is no grid point.
inline std::optional<IntPoint> as_grid_point(const Point& p) {
  // w = 1 (input vertices, stored by to_point): the numerators are the
  // coordinates (stored_grid_point).
  if (p.w == PointW(1)) return stored_grid_point(p);
  std::int64_t g[3];
  for (int axis = 0; axis < 3; ++axis) {
    const double f = p.f[axis];
    if (!(std::fabs(f) <= static_cast<double>(kCoordLimit) + 1)) return std::nullopt;  // f may err past 2^25
    const double nearest = std::nearbyint(f);
    if (std::fabs(nearest) > static_cast<double>(kCoordLimit)) return std::nullopt;
    if (std::fabs(f - nearest) > 0x1p-20) return std::nullopt;  // an integer x/w is within 2^-25 of f
    g[axis] = static_cast<std::int64_t>(nearest);
    if (compare(Coord(g[axis]) * p.w, detail::coord(p, axis)) != 0) return std::nullopt;
  }
  return IntPoint{g[0], g[1], g[2]};
}
static_assert(std::is_same_v<decltype(Coord{} * PointW{}), PointXYZ>, "grid coordinate times w: 26 + 162 = 188");

/// Lexicographic order of the coordinates (x, then y, then z): -1, 0, +1.
inline int compare_lex(const Point& a, const Point& b) {
  for (int axis = 0; axis < 3; ++axis)
    if (const int c = compare_coord(a, b, axis)) return c;
  return 0;
}

namespace detail {
/// orient2d_dropped's exact evaluation, for the few calls its filter cannot
/// decide: out of line, so that the filter inlines into the hot loops (ear
/// clipping calls it tens of thousands of times per curved result).
[[gnu::noinline]] inline int orient2d_exact(const Point& a, const Point& b, const Point& c, int u, int v) {
  // det [a_u a_v a_w; b_u b_v b_w; c_u c_v c_w] = a_w b_w c_w * (2D orientation); w > 0.
  const PointXYZ &xu = coord(a, u), &xv = coord(a, v);
  const PointXYZ &yu = coord(b, u), &yv = coord(b, v);
  const PointXYZ &zu = coord(c, u), &zv = coord(c, v);
  const ProjectedMinor m_bc = yu * zv - yv * zu;
  const ProjectedMinor m_ac = xu * zv - xv * zu;
  const ProjectedMinor m_ab = xu * yv - xv * yu;
  const Orient2Value d = a.w * m_bc - b.w * m_ac + c.w * m_ab;
  return d.sign();
}
}  // namespace detail

/// The coordinates (u, v) = (drop + 1, drop + 2) mod 3 that remain when axis
/// `drop` is projected away (without the divisions of % 3).
constexpr std::array<int, 2> projected_axes(int drop) { return {drop == 2 ? 0 : drop + 1, drop == 0 ? 2 : drop - 1}; }
static_assert(projected_axes(0) == std::array<int, 2>{1, 2} && projected_axes(1) == std::array<int, 2>{2, 0} &&
              projected_axes(2) == std::array<int, 2>{0, 1});

/// orient2d_dropped with the projection's axes given (projected_axes:
/// callers that orient many triples in one plane compute them once).
inline int orient2d_uv(const Point& a, const Point& b, const Point& c, int u, int v) {
  const double au = a.f[u], av = a.f[v], bu = b.f[u], bv = b.f[v], cu = c.f[u], cv = c.f[v];
  const double det = (bu - au) * (cv - av) - (bv - av) * (cu - au);
  // std::max, not std::fmax (a libm call each): the approximations are
  // finite, and a NaN det would fail both tests below and go exact anyway.
  const double m = std::max({std::fabs(au), std::fabs(av), std::fabs(bu), std::fabs(bv), std::fabs(cu), std::fabs(cv)});
  const double bound = 256 * 0x1p-53 * m * m;
  if (det > bound) return 1;
  if (det < -bound) return -1;
  return detail::orient2d_exact(a, b, c, u, v);
}

/// Orientation of a, b, c projected along `drop` onto the coordinates
/// (u, v) = (drop+1, drop+2) mod 3: +1 counter-clockwise, -1 clockwise, 0
/// collinear. Seen from the +e_drop side, so for points on a plane whose
/// normal has a positive component along `drop`, +1 means counter-clockwise
/// around that normal.
inline int orient2d_dropped(const Point& a, const Point& b, const Point& c, int drop) {
  const auto [u, v] = projected_axes(drop);
  return orient2d_uv(a, b, c, u, v);
}

}  // namespace ember
