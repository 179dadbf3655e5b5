#pragma once
// Axis-parallel lines through dyadic points, met with polygons in reduced
// width (paper Section 4.5.5: "many intermediate results can be safely
// computed with reduced bit sizes").
//
// The line {x_u = U/2^s, x_v = V/2^s} (u, v the two axes other than `axis`)
// meets a supporting plane n·x + d = 0 with n_axis != 0 at the homogeneous
// point  x_axis = -(n_u U + n_v V + d 2^s),  x_u = U n_axis,  x_v = V n_axis,
// w = n_axis 2^s  (all scaled by the same factor, then signed so w > 0).
// No 3x3 determinant is needed and every value stays far below 243 bits.
#include <array>
#include <cmath>
#include <cstdint>

#include "geometry/intersect.hpp"

namespace ember {

using DyadicNum = Int<78>;    ///< |U| <= 2^25 * 2^52 = 2^77 < 2^78
using DyadicScale = Int<54>;  ///< 2^s with s <= 52 < 2^54
/// n_u U + n_v V + d 2^s: (53+78 = 131) + (131) -> 132, + (79+54 = 133) -> 134.
using AxisPointCoord = Int<134>;
using AxisPointW = Int<107>;  ///< n_axis 2^s: 53+54 = 107
/// classify: 53+134 = 187 and 79+107 = 186 per term, pairwise sums -> 189 (vs 243 in general).
using AxisClassifyValue = Int<189>;

/// A point on an axis-parallel line, homogeneous with w > 0.
struct AxisPoint {
  int axis = 0;
  AxisPointCoord c[3];  ///< coordinates times w
  AxisPointW w;
  /// c[i] / w in double (each limb conversion, w and the division round:
  /// relative error < 8 units in the last place, as for Point::f).
  std::array<double, 3> f{};
};

/// The axis-parallel line through dyadic (U, V)/2^s on the other two axes.
struct AxisLine {
  int axis = 0;    ///< direction of the line
  DyadicNum u, v;  ///< numerators on axes (axis+1)%3 and (axis+2)%3
  int shift = 0;   ///< common denominator 2^shift, shift <= 52
};

namespace detail {
/// n_u U + n_v V + d 2^s: the line's offset from the plane, times 2^s.
inline auto axis_line_offset(const AxisLine& l, const Plane& p) {
  const DyadicScale scale(std::int64_t{1} << l.shift);
  const int u = (l.axis + 1) % 3, v = (l.axis + 2) % 3;
  return p.normal(u) * l.u + p.normal(v) * l.v + p.d * scale;
}
}  // namespace detail

/// Where the line meets the plane; false if parallel (then *in_plane tells
/// whether the line lies in the plane).
inline bool meet(const AxisLine& l, const Plane& p, AxisPoint& out, bool* in_plane = nullptr) {
  const NormalCoef& na = p.normal(l.axis);
  const auto off = detail::axis_line_offset(l, p);
  static_assert(std::is_same_v<std::remove_cv_t<decltype(off)>, AxisPointCoord>,
                "offset: 131 + 131 -> 132, + 133 -> 134 bits");
  if (na.is_zero()) {
    if (in_plane) *in_plane = off.is_zero();
    return false;
  }
  const int u = (l.axis + 1) % 3, v = (l.axis + 2) % 3;
  const bool flip = na.negative();
  const DyadicScale scale(std::int64_t{1} << l.shift);
  AxisPointCoord cu = l.u * na, cv = l.v * na;
  AxisPointCoord ca = -off;
  AxisPointW w = na * scale;
  if (flip) {
    cu = -cu;
    cv = -cv;
    ca = -ca;
    w = -w;
  }
  out.axis = l.axis;
  out.c[l.axis] = ca;
  out.c[u] = cu;
  out.c[v] = cv;
  out.w = w;
  const double fw = w.to_double();
  out.f = {out.c[0].to_double() / fw, out.c[1].to_double() / fw, out.c[2].to_double() / fw};
  return true;
}

/// Exact side of x relative to p.
inline int classify_exact(const AxisPoint& x, const Plane& p) {
  const AxisClassifyValue s = (p.a * x.c[0] + p.b * x.c[1]) + (p.c * x.c[2] + p.d * x.w);
  return s.sign();
}

/// Side of x relative to p, with the floating-point filter of
/// classify(const Point&, const Plane&) (same error bound, same derivation).
inline int classify(const AxisPoint& x, const Plane& p) {
  return detail::filtered_sign(x.f, p, [&] { return classify_exact(x, p); });
}

inline std::array<double, 3> approx(const AxisPoint& x) {
  const double w = x.w.to_double();
  return {x.c[0].to_double() / w, x.c[1].to_double() / w, x.c[2].to_double() / w};
}

/// The line's (U, V) / 2^s in double, each correctly rounded.
inline std::array<double, 2> line_point_approx(const AxisLine& l) {
  return {std::ldexp(l.u.to_double(), -l.shift), std::ldexp(l.v.to_double(), -l.shift)};
}

/// Floating-point filter for the hit test below: true only when the line
/// certainly misses the polygon, i.e. its point (U, V) lies strictly outside
/// an edge of the polygon's projection along the line (valid when the
/// polygon is not parallel to the line: the projection is then one-to-one
/// and keeps the convex polygon's orientation, counter-clockwise iff
/// n_axis > 0). False means "don't know".
/// Error bound: |coordinates| < 2^26; the cached vertices err by at most 8
/// ulps (< 2^-23 each), U/2^s and V/2^s are correctly rounded (< 2^-27), so
/// each difference below errs by < 2^-21 (its own rounding included) and the
/// orientation o = du dv' - dv du' by < 2^-21 (D + E) + 2^-42 + 2^-51 D E
/// (D, E the L1 lengths of the two difference vectors, both products and the
/// subtraction rounding). The margin is twice that, plus 2^-36 because D and
/// E are themselves computed (each within 2^-19 of the true lengths).
/// `uv` = line_point_approx(l), computed once per line by the caller.
/// `na` is the sign of the polygon's normal along the line, `vertex(i)` gives
/// vertex i's approximation (within those 8 ulps; exact is fine).
template <typename VertexApprox>
inline bool line_clearly_misses(const AxisLine& l, const std::array<double, 2>& uv, int na, std::size_t n,
                                VertexApprox&& vertex) {
  if (na == 0) return false;
  const int u = (l.axis + 1) % 3, v = (l.axis + 2) % 3;
  const double U = uv[0], V = uv[1];
  for (std::size_t i = 0; i < n; ++i) {
    const std::array<double, 3>& a = vertex(i);
    const std::array<double, 3>& b = vertex(i + 1 == n ? 0 : i + 1);
    const double du = b[u] - a[u], dv = b[v] - a[v], eu = U - a[u], ev = V - a[v];
    const double o = du * ev - dv * eu;
    const double D = std::fabs(du) + std::fabs(dv), E = std::fabs(eu) + std::fabs(ev);
    const double margin = 0x1p-20 * (D + E) + 0x1p-36 + 0x1p-50 * D * E;
    if (na * o < -margin) return true;  // strictly right of a counter-clockwise edge: outside
  }
  return false;
}

inline bool line_clearly_misses(const AxisLine& l, const std::array<double, 2>& uv, const Polygon& poly) {
  return line_clearly_misses(l, uv, poly.support.normal(l.axis).sign(), poly.vertices.size(),
                             [&](std::size_t i) -> const std::array<double, 3>& { return poly.vertices[i].f; });
}

/// Segment of the line with classify(r0) <= 0 and classify(r1) <= 0 against a
/// polygon; same answers as intersect_segment for the same line planes.
inline SegmentHit intersect_segment(const AxisLine& l, const Plane& r0, const Plane& r1, const Polygon& poly) {
  AxisPoint x;
  bool in_plane = false;
  if (!meet(l, poly.support, x, &in_plane)) return {in_plane ? LineHit::InPlane : LineHit::Miss, false};
  const int c0 = classify(x, r0), c1 = classify(x, r1);
  if (c0 > 0 || c1 > 0) return {LineHit::Miss, false};
  const int loc = locate(poly, x);
  if (loc > 0) return {LineHit::Miss, false};
  return {loc == 0 ? LineHit::Boundary : LineHit::Interior, c0 == 0 || c1 == 0};
}

}  // namespace ember
