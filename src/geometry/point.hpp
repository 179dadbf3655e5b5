#pragma once
// Homogeneous points as intersections of three planes (Cramer's rule with
// integer minors, paper Eq. 3) and their classification against planes (Eq. 4).
#include <array>
#include <cmath>
#include <optional>

#include "geometry/plane.hpp"

namespace ember {

/// The point (x/w, y/w, z/w); w > 0 always (normalized on creation).
/// The representation is not canonical: the same point may be stored with
/// different scales. Compare points by incidence (classify == 0), not by value.
struct Point {
  PointXYZ x, y, z;
  PointW w;
  /// Cached x/w, y/w, z/w in double, set on creation (detail::normalize_w,
  /// to_point): each within 8 units in the last place (<= 3 roundings in
  /// converting the limbs, 3 in w, 1 in the division). Feeds the filter in
  /// classify(); never used for a decision on its own.
  std::array<double, 3> f{};
};

namespace detail {
inline void cache_approx(Point& pt) {
  const double w = pt.w.to_double();
  pt.f = {pt.x.to_double() / w, pt.y.to_double() / w, pt.z.to_double() / w};
}
}  // namespace detail

/// A grid point with w = 1.
inline Point to_point(const IntPoint& p) {
  Point pt{PointXYZ(p.x), PointXYZ(p.y), PointXYZ(p.z), PointW(1), {}};
  pt.f = {static_cast<double>(p.x), static_cast<double>(p.y), static_cast<double>(p.z)};
  return pt;
}

namespace detail {
/// Null vector of the 3x4 matrix [p; q; r] without normalizing the sign of w:
/// X_j = (-1)^j det(matrix without column j), so <s, X> = det[s; p; q; r] for any
/// plane s and <p, X> = <q, X> = <r, X> = 0. The six 2x2 minors of rows (p, q)
/// are computed once and shared by all four 3x3 determinants (expanded along r).
/// Returns false iff w = 0 (normals linearly dependent); x, y, z are filled anyway
/// (all of x, y, z, w vanish iff the three planes share a line).
inline bool intersect_raw(const Plane& p, const Plane& q, const Plane& r, Point& out) {
  const NormalMinor m_ab = p.a * q.b - p.b * q.a;
  const NormalMinor m_ac = p.a * q.c - p.c * q.a;
  const NormalMinor m_bc = p.b * q.c - p.c * q.b;
  const OffsetMinor m_ad = p.a * q.d - p.d * q.a;
  const OffsetMinor m_bd = p.b * q.d - p.d * q.b;
  const OffsetMinor m_cd = p.c * q.d - p.d * q.c;
  // det over columns (i,j,k) of [p; q; r] = r_i m_jk - r_j m_ik + r_k m_ij.
  const PointW det_abc = r.a * m_bc - r.b * m_ac + r.c * m_ab;    // 53+107 = 160, three terms -> 162
  const PointXYZ det_bcd = r.b * m_cd - r.c * m_bd + r.d * m_bc;  // 53+133 = 79+107 = 186 -> 188
  const PointXYZ det_acd = r.a * m_cd - r.c * m_ad + r.d * m_ac;  // same
  const PointXYZ det_abd = r.a * m_bd - r.b * m_ad + r.d * m_ab;  // same
  // X = (+det_bcd, -det_acd, +det_abd, -det_abc).
  out.x = det_bcd;
  out.y = -det_acd;
  out.z = det_abd;
  out.w = -det_abc;
  return !det_abc.is_zero();
}
static_assert(
    std::is_same_v<decltype(NormalCoef{} * NormalMinor{} - NormalCoef{} * NormalMinor{} + NormalCoef{} * NormalMinor{}),
                   PointW>,
    "x4: normal (53) * normal minor (107) = 160, three terms -> 162");
static_assert(
    std::is_same_v<decltype(NormalCoef{} * OffsetMinor{} - NormalCoef{} * OffsetMinor{} + OffsetCoef{} * NormalMinor{}),
                   PointXYZ>,
    "x1..x3: 53+133 = 79+107 = 186 per term, three terms -> 188");

/// intersect_raw(p, q, axis_plane(axis, t), out), with the zero products of the
/// unit axis normal left out (r = e_axis, r.d = -t). Same bounds: every term is
/// a minor (<= 133 bits) or t (26) times a minor (<= 26+107 = 133).
inline bool intersect_raw_axis(const Plane& p, const Plane& q, int axis, std::int64_t t, Point& out) {
  const NormalMinor m_ab = p.a * q.b - p.b * q.a;
  const NormalMinor m_ac = p.a * q.c - p.c * q.a;
  const NormalMinor m_bc = p.b * q.c - p.c * q.b;
  const Coord nt(-t);  // r.d
  PointW det_abc;
  PointXYZ det_bcd, det_acd, det_abd;
  if (axis == 0) {
    det_abc = m_bc;
    det_bcd = nt * m_bc;
    det_acd = (p.c * q.d - p.d * q.c) + nt * m_ac;
    det_abd = (p.b * q.d - p.d * q.b) + nt * m_ab;
  } else if (axis == 1) {
    det_abc = -m_ac;
    det_bcd = (p.c * q.d - p.d * q.c) + nt * m_bc;
    det_acd = nt * m_ac;
    det_abd = -(p.a * q.d - p.d * q.a) + nt * m_ab;
  } else {
    det_abc = m_ab;
    det_bcd = -(p.b * q.d - p.d * q.b) + nt * m_bc;
    det_acd = -(p.a * q.d - p.d * q.a) + nt * m_ac;
    det_abd = nt * m_ab;
  }
  out.x = det_bcd;
  out.y = -det_acd;
  out.z = det_abd;
  out.w = -det_abc;
  return !det_abc.is_zero();
}

/// Makes w positive and caches the double approximation: the last step of
/// creating every computed point.
inline void normalize_w(Point& pt) {
  if (pt.w.negative()) {
    pt.x = -pt.x;
    pt.y = -pt.y;
    pt.z = -pt.z;
    pt.w = -pt.w;
  }
  cache_approx(pt);
}
}  // namespace detail

/// The common point of three planes; nullopt iff their normals are linearly
/// dependent (w = 0). The order of the planes only affects the (normalized) scale.
inline std::optional<Point> intersect(const Plane& p, const Plane& q, const Plane& r) {
  Point pt;
  if (!detail::intersect_raw(p, q, r, pt)) return std::nullopt;
  detail::normalize_w(pt);
  return pt;
}

/// <X, plane> = a*x + b*y + c*z + d*w; its sign is the side of the point since w > 0.
inline ClassifyValue classify_value(const Point& pt, const Plane& s) {
  return (s.a * pt.x + s.b * pt.y) + (s.c * pt.z + s.d * pt.w);
}
static_assert(std::is_same_v<decltype((NormalCoef{} * PointXYZ{} + NormalCoef{} * PointXYZ{}) +
                                      (NormalCoef{} * PointXYZ{} + OffsetCoef{} * PointW{})),
                             ClassifyValue>,
              "classify: 53+188 = 79+162 = 241 per term, pairwise sums -> 243");

/// The grid point that pt is when it is stored with w = 1 and coordinates
/// within the grid (|x| <= kCoordLimit): how triangles keep their corners
/// (to_point), so most vertices of the leaves' and cuts' polygons. Limb
/// tests only; nullopt for any other representation, even of a grid point.
inline std::optional<IntPoint> stored_grid_point(const Point& pt) {
  if (!(pt.w == PointW(1))) return std::nullopt;
  std::int64_t g[3];
  const PointXYZ* coords[3] = {&pt.x, &pt.y, &pt.z};
  for (int axis = 0; axis < 3; ++axis) {
    g[axis] = static_cast<std::int64_t>(coords[axis]->limb(0));
    if (g[axis] < -kCoordLimit || g[axis] > kCoordLimit || !(*coords[axis] == PointXYZ(g[axis]))) return std::nullopt;
  }
  return IntPoint{g[0], g[1], g[2]};
}

/// Exact side of `pt` relative to `s`: -1, 0, +1 (0: pt lies on s). A point
/// stored as a grid point takes the 82-bit integer classify (one __int128)
/// instead of the 243-bit one: the filter's undecided cases are mostly
/// vertices lying on the plane, shared input vertices among them.
inline int classify_exact(const Point& pt, const Plane& s) {
  if (const std::optional<IntPoint> g = stored_grid_point(pt)) return classify(*g, s);
  return classify_value(pt, s).sign();
}

/// A plane's coefficients as doubles, for the classification filter: a, b, c
/// exactly (|n| <= 2^52), d rounded once (error < u). Converting d (an int128)
/// costs a library call, so loops over many points convert the plane once.
struct PlaneApprox {
  double a, b, c, d;
  explicit PlaneApprox(const Plane& s)
      : a(static_cast<double>(s.a.raw())),
        b(static_cast<double>(s.b.raw())),
        c(static_cast<double>(s.c.raw())),
        d(static_cast<double>(s.d.raw())) {}
};

/// -1, 0, +1: side of `pt` relative to `s` (0: pt lies on s). A floating-point
/// filter answers when the double estimate v = a x~ + b y~ + c z~ + d~ is
/// clearly away from zero, else the exact 243-bit predicate decides.
/// Error bound (u = 2^-53): x~ has relative error < 8u (Point::f), a, b, c are
/// exact doubles (|n| <= 2^52), d~ errs < u, each product adds u, the three
/// sums add < 3u of m = sum of |terms|: |v - V/w| < 13u m < 2^-48 m. Exact
/// zeros (V = 0) always fall through to the exact path.
namespace detail {
/// The filter shared by every classify of a point with cached double
/// coordinates f (relative error < 8u each): the sign of a f0 + b f1 + c f2 + d
/// when it is clearly away from zero, else exact().
template <typename Exact>
inline int filtered_sign(const std::array<double, 3>& f, const PlaneApprox& s, Exact&& exact) {
  const double t0 = s.a * f[0];
  const double t1 = s.b * f[1];
  const double t2 = s.c * f[2];
  const double t3 = s.d;
  const double v = (t0 + t1) + (t2 + t3);
  const double m = (std::fabs(t0) + std::fabs(t1)) + (std::fabs(t2) + std::fabs(t3));
  const double bound = m * 0x1p-48;
  if (v > bound) return 1;
  if (v < -bound) return -1;
  return exact();
}
template <typename Exact>
inline int filtered_sign(const std::array<double, 3>& f, const Plane& s, Exact&& exact) {
  return filtered_sign(f, PlaneApprox(s), exact);
}
}  // namespace detail

inline int classify(const Point& pt, const Plane& s) {
  return detail::filtered_sign(pt.f, s, [&] { return classify_exact(pt, s); });
}
/// classify with s's coefficients already converted (`approx` = PlaneApprox(s)):
/// for loops that test many points against one plane.
inline int classify(const Point& pt, const Plane& s, const PlaneApprox& approx) {
  return detail::filtered_sign(pt.f, approx, [&] { return classify_exact(pt, s); });
}

/// Fast path for an axis plane x_axis = position (as made by axis_plane):
/// sign(x_axis - position*w): 162+26 = 188 bits per product, 189 after the
/// difference, instead of the 243-bit general classify.
inline int classify_axis(const Point& pt, int axis, std::int64_t position) {
  const PointXYZ& c = axis == 0 ? pt.x : (axis == 1 ? pt.y : pt.z);
  return (c - pt.w * Coord(position)).sign();
}

/// Approximate Cartesian coordinates, for heuristics and output only.
inline const std::array<double, 3>& approx(const Point& pt) { return pt.f; }

}  // namespace ember
