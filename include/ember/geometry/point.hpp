#pragma once
// Homogeneous points as intersections of three planes (Cramer's rule with
// integer minors, paper Eq. 3) and their classification against planes (Eq. 4).
#include <array>
#include <optional>

#include "ember/geometry/plane.hpp"

namespace ember {

/// The point (x/w, y/w, z/w); w > 0 always (normalized on creation).
/// The representation is not canonical: the same point may be stored with
/// different scales. Compare points by incidence (classify == 0), not by value.
struct Point {
  PointXYZ x, y, z;
  PointW w;
};

/// A grid point with w = 1.
inline Point to_point(const IntPoint& p) {
  return Point{PointXYZ(p.x), PointXYZ(p.y), PointXYZ(p.z), PointW(1)};
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
  const PointW det_abc = r.a * m_bc - r.b * m_ac + r.c * m_ab;     // 53+107 = 160, three terms -> 162
  const PointXYZ det_bcd = r.b * m_cd - r.c * m_bd + r.d * m_bc;   // 53+133 = 79+107 = 186 -> 188
  const PointXYZ det_acd = r.a * m_cd - r.c * m_ad + r.d * m_ac;   // same
  const PointXYZ det_abd = r.a * m_bd - r.b * m_ad + r.d * m_ab;   // same
  // X = (+det_bcd, -det_acd, +det_abd, -det_abc).
  out.x = det_bcd;
  out.y = -det_acd;
  out.z = det_abd;
  out.w = -det_abc;
  return !det_abc.is_zero();
}
static_assert(std::is_same_v<decltype(NormalCoef{} * NormalMinor{} - NormalCoef{} * NormalMinor{} +
                                      NormalCoef{} * NormalMinor{}),
                             PointW>,
              "x4: normal (53) * normal minor (107) = 160, three terms -> 162");
static_assert(std::is_same_v<decltype(NormalCoef{} * OffsetMinor{} - NormalCoef{} * OffsetMinor{} +
                                      OffsetCoef{} * NormalMinor{}),
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

inline void normalize_w(Point& pt) {
  if (pt.w.negative()) {
    pt.x = -pt.x;
    pt.y = -pt.y;
    pt.z = -pt.z;
    pt.w = -pt.w;
  }
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

/// -1, 0, +1: side of `pt` relative to `s` (0: pt lies on s).
inline int classify(const Point& pt, const Plane& s) { return classify_value(pt, s).sign(); }

/// Fast path for an axis plane x_axis = position (as made by axis_plane):
/// sign(x_axis - position*w): 162+26 = 188 bits per product, 189 after the
/// difference, instead of the 243-bit general classify.
inline int classify_axis(const Point& pt, int axis, std::int64_t position) {
  const PointXYZ& c = axis == 0 ? pt.x : (axis == 1 ? pt.y : pt.z);
  return (c - pt.w * Coord(position)).sign();
}

/// Approximate Cartesian coordinates, for heuristics and output only.
inline std::array<double, 3> approx(const Point& pt) {
  const double w = pt.w.to_double();
  return {pt.x.to_double() / w, pt.y.to_double() / w, pt.z.to_double() / w};
}

}  // namespace ember
