#pragma once
// Planes with exact integer coefficients and their constructions from grid
// points (paper Section 3). A plane (a,b,c,d) is the set a*x+b*y+c*z+d = 0; its
// positive side is where the expression is > 0. Kinds: S (supporting plane of
// a triangle), E (edge plane, parallel to the dominant axis of the support) and
// A (axis-aligned at an integer position). Bounds: see bounds.hpp.
#include <array>
#include <cstdint>
#include <optional>
#include <string>

#include "ember/error.hpp"
#include "geometry/bounds.hpp"

namespace ember {

/// A grid point; every coordinate satisfies |x| <= kCoordLimit.
struct IntPoint {
  std::int64_t x = 0, y = 0, z = 0;
  friend bool operator==(const IntPoint&, const IntPoint&) = default;
};

inline bool in_range(const IntPoint& p) {
  auto ok = [](std::int64_t v) { return v >= -kCoordLimit && v <= kCoordLimit; };
  return ok(p.x) && ok(p.y) && ok(p.z);
}

namespace detail {
/// The error path, kept out of line so the range check inlines into callers.
[[noreturn, gnu::noinline, gnu::cold]] inline void throw_out_of_range(const IntPoint& p) {
  throw Error("ember geometry: grid point (" + std::to_string(p.x) + ", " + std::to_string(p.y) + ", " +
              std::to_string(p.z) + ") exceeds the coordinate limit 2^25; quantize the input into [-2^25, 2^25]");
}
inline void require_in_range(const IntPoint& p) {
  if (!in_range(p)) [[unlikely]]
    throw_out_of_range(p);
}
}  // namespace detail

struct Plane {
  NormalCoef a, b, c;
  OffsetCoef d;

  /// Coefficient-wise equality (not geometric: 2*p and p compare unequal; use coplanar()).
  friend bool operator==(const Plane& p, const Plane& q) {
    return p.a == q.a && p.b == q.b && p.c == q.c && p.d == q.d;
  }
  /// The same plane with the opposite orientation (positive and negative sides swapped).
  friend Plane operator-(const Plane& p) { return Plane{-p.a, -p.b, -p.c, -p.d}; }

  /// Normal component k (0 = a, 1 = b, 2 = c).
  const NormalCoef& normal(int k) const { return k == 0 ? a : (k == 1 ? b : c); }
};

/// Plane through p0, p1, p2 with normal n = (p1-p0) x (p2-p0): seen from the
/// positive side, p0 -> p1 -> p2 is counter-clockwise (outward for CCW-oriented
/// closed meshes). d = -n.p0. nullopt if the points are collinear (n = 0).
/// Throws ember::Error if a coordinate exceeds kCoordLimit.
inline std::optional<Plane> supporting_plane(const IntPoint& p0, const IntPoint& p1, const IntPoint& p2) {
  detail::require_in_range(p0);
  detail::require_in_range(p1);
  detail::require_in_range(p2);
  const CoordDiff ux = Coord(p1.x) - Coord(p0.x), uy = Coord(p1.y) - Coord(p0.y), uz = Coord(p1.z) - Coord(p0.z);
  const CoordDiff vx = Coord(p2.x) - Coord(p0.x), vy = Coord(p2.y) - Coord(p0.y), vz = Coord(p2.z) - Coord(p0.z);
  // The type system derives 27+27+1 = 55 bits; each component is twice the area
  // of the triangle projected onto a coordinate plane, within a square of side
  // 2^26, hence <= 2^52 < 2^53 (bounds.hpp).
  const auto nx = NormalCoef::assume_bound(uy * vz - uz * vy);
  const auto ny = NormalCoef::assume_bound(uz * vx - ux * vz);
  const auto nz = NormalCoef::assume_bound(ux * vy - uy * vx);
  if (nx.is_zero() && ny.is_zero() && nz.is_zero()) return std::nullopt;
  // 53+26 = 79 per product, 81 after the sum; |n.p0| <= 3*2^52*2^25 < 2^79.
  const auto d = OffsetCoef::assume_bound(-(nx * Coord(p0.x) + ny * Coord(p0.y) + nz * Coord(p0.z)));
  return Plane{nx, ny, nz, d};
}

/// (p1 - p0) x (p2 - p0) in plain int64, for grid points (|x| <= kCoordLimit,
/// not checked): corner differences are at most 2^26, so each product is at
/// most 2^52 and each component below 2^53. Zero iff the points are collinear;
/// the same vector as supporting_plane's normal.
inline std::array<std::int64_t, 3> grid_normal(const IntPoint& p0, const IntPoint& p1, const IntPoint& p2) {
  static_assert(kCoordLimit <= (std::int64_t{1} << 25) && 2 * 26 + 1 < 63,
                "grid normal: differences <= 2^26, products <= 2^52, components < 2^53 fit int64");
  const std::int64_t ux = p1.x - p0.x, uy = p1.y - p0.y, uz = p1.z - p0.z;
  const std::int64_t vx = p2.x - p0.x, vy = p2.y - p0.y, vz = p2.z - p0.z;
  return {uy * vz - uz * vy, uz * vx - ux * vz, ux * vy - uy * vx};
}

/// n . (p - origin) exactly, for a grid normal n (grid_normal of a triangle
/// with corner `origin`) and a grid point p: the side of p against that
/// triangle's plane (sign) in plain __int128. Differences are at most 2^26,
/// so each product is below 2^53 * 2^27 = 2^80 and the sum below 2^82.
inline __int128 grid_side(const IntPoint& origin, const std::array<std::int64_t, 3>& n, const IntPoint& p) {
  static_assert(kCoordLimit <= (std::int64_t{1} << 25) && 53 + 27 + 2 < 127,
                "grid side: normal < 2^53 times difference < 2^27, three terms < 2^82");
  return __int128{n[0]} * (p.x - origin.x) + __int128{n[1]} * (p.y - origin.y) + __int128{n[2]} * (p.z - origin.z);
}

/// det[b - a; c - a; d - a] = ((b - a) x (c - a)) . (d - a) exactly, for
/// grid points: positive when d lies on the positive side of the plane
/// (a, b, c) with normal (b - a) x (c - a). Differences are below 2^26, the
/// cross product's components below 2^53 (int64) and the sum of three
/// products below 2^81 (__int128).
inline __int128 grid_orient3d(const IntPoint& a, const IntPoint& b, const IntPoint& c, const IntPoint& d) {
  static_assert(kCoordLimit <= (std::int64_t{1} << 25) && 2 * 26 + 1 < 63 && 53 + 26 + 2 < 127,
                "grid orient3d: differences < 2^26, cross product < 2^53 in int64, three terms < 2^81");
  const std::int64_t bx = b.x - a.x, by = b.y - a.y, bz = b.z - a.z;
  const std::int64_t cx = c.x - a.x, cy = c.y - a.y, cz = c.z - a.z;
  return __int128{by * cz - bz * cy} * (d.x - a.x) + __int128{bz * cx - bx * cz} * (d.y - a.y) +
         __int128{bx * cy - by * cx} * (d.z - a.z);
}

/// Axis (0, 1, 2) of the largest |normal component|; ties go to the lowest index.
inline int dominant_axis(const Plane& p) {
  const std::int64_t ax = p.a.abs().raw(), ay = p.b.abs().raw(), az = p.c.abs().raw();
  if (ax >= ay && ax >= az) return 0;
  return ay >= az ? 1 : 2;
}

/// Plane through the edge p0 -> p1 of a polygon on `support`, parallel to the
/// dominant axis e_k of the support normal: m = sign(n_k) * (p1-p0) x e_k. The
/// polygon interior (for CCW vertex order around the support normal) lies on the
/// NEGATIVE side. Components |m_i| <= 2^26, |d| <= 2^52. The edge must not be
/// degenerate (p0 != p1; an edge in the support plane is never parallel to e_k).
inline Plane edge_plane(const IntPoint& p0, const IntPoint& p1, const Plane& support) {
  detail::require_in_range(p0);
  detail::require_in_range(p1);
  const int k = dominant_axis(support);
  const bool flip = support.normal(k).negative();
  const std::int64_t ex = p1.x - p0.x, ey = p1.y - p0.y, ez = p1.z - p0.z;
  // (ex,ey,ez) x e_k: k=0 -> (0, ez, -ey); k=1 -> (-ez, 0, ex); k=2 -> (ey, -ex, 0).
  std::int64_t m[3] = {0, 0, 0};
  if (k == 0) {
    m[1] = ez, m[2] = -ey;
  } else if (k == 1) {
    m[0] = -ez, m[2] = ex;
  } else {
    m[0] = ey, m[1] = -ex;
  }
  if (flip) m[0] = -m[0], m[1] = -m[1], m[2] = -m[2];
  // |m_i| <= 2^26 and |p0_i| <= 2^25, two non-zero terms: |d| <= 2^52, fits int64.
  const std::int64_t d = -(m[0] * p0.x + m[1] * p0.y + m[2] * p0.z);
  return Plane{m[0], m[1], m[2], d};
}

/// The plane x_axis = position with normal +e_axis (positive side: larger coordinate).
inline Plane axis_plane(int axis, std::int64_t position) {
  if (axis < 0 || axis > 2)
    throw Error("ember geometry: axis_plane axis must be 0, 1 or 2, got " + std::to_string(axis));
  if (position < -kCoordLimit || position > kCoordLimit)
    throw Error("ember geometry: axis_plane position " + std::to_string(position) +
                " exceeds the coordinate limit 2^25");
  Plane p{0, 0, 0, -position};
  if (axis == 0) p.a = 1;
  if (axis == 1) p.b = 1;
  if (axis == 2) p.c = 1;
  return p;
}

/// Normals are parallel (either orientation): n_p x n_q = 0.
inline bool parallel(const Plane& p, const Plane& q) {
  return (p.b * q.c - p.c * q.b).is_zero() && (p.c * q.a - p.a * q.c).is_zero() && (p.a * q.b - p.b * q.a).is_zero();
}

/// Same geometric plane (either orientation): (a,b,c,d) of p and q are proportional.
inline bool coplanar(const Plane& p, const Plane& q) {
  if (!parallel(p, q)) return false;
  // Parallel normals; the planes coincide iff d is scaled like the normal, i.e.
  // every minor n_i d_q - n_qi d_p vanishes (53+79 = 132 bits per product).
  return (p.a * q.d - q.a * p.d).is_zero() && (p.b * q.d - q.b * p.d).is_zero() && (p.c * q.d - q.c * p.d).is_zero();
}

/// Normals point the same way (n_p . n_q > 0). Meaningful for parallel planes.
inline bool same_orientation(const Plane& p, const Plane& q) { return (p.a * q.a + p.b * q.b + p.c * q.c).sign() > 0; }

/// Side of a grid point: sign(a*x + b*y + c*z + d). 82 bits, one __int128.
inline int classify(const IntPoint& x, const Plane& p) {
  const IntClassifyValue v = p.a * Coord(x.x) + p.b * Coord(x.y) + p.c * Coord(x.z) + p.d;
  return v.sign();
}
static_assert(
    std::is_same_v<decltype(NormalCoef{} * Coord{} + NormalCoef{} * Coord{} + NormalCoef{} * Coord{} + OffsetCoef{}),
                   IntClassifyValue>,
    "integer classify: 53+26 = 79, three products -> 81, + d(79) -> 82");

}  // namespace ember
