#pragma once
// Internal data of the Boolean core: the polygon soup of a subproblem, its
// integer box, dyadic reference points and winding-number vectors.
#include <array>
#include <cmath>
#include <cstdint>
#include <memory>
#include <span>
#include <vector>

#include "geometry/geometry.hpp"

namespace ember::core {

/// A convex polygon of the soup, tagged with its operand (its winding-number
/// transition vector is that operand's unit vector) and a global id that
/// orders coincident polygons (Fig. 8: the lowest id emits an overlap).
///
/// An input triangle that no split has cut yet is stored *unbuilt*: `poly` is
/// null and `corners` points at its grid corners (GridTriangles::corners[id],
/// alive for the whole Boolean; kept when it is built or cut, so that a leaf
/// can emit it unbuilt again). The entry itself is 80 bytes, the polygon
/// behind `poly` only exists where it is needed.
/// Most triangles lie far from the other operands and leave the subdivision
/// through an early-out without ever being clipped or traced; building their
/// plane-based form (~500 bytes of edge planes and homogeneous vertices on
/// the heap) up front was the set-up's main cost and the soup's main memory.
/// materialize() builds it where it is needed: before a clip that cuts the
/// triangle, at a leaf, and for an exact trace test.
struct SoupPolygon {
  std::unique_ptr<Polygon> poly;     ///< null while unbuilt
  std::uint32_t id = 0;              ///< input triangle index, unique
  std::uint32_t operand = 0;         ///< which operand's surface this is
  std::array<double, 3> lo{}, hi{};  ///< conservative bounding box (grid units)
  /// How many subdivision splits made this piece of its input triangle (255:
  /// that many or more). The pieces of one triangle are the leaves of a binary
  /// tree of splits, so their shares 2^-splits sum to exactly 1.
  std::uint8_t splits = 0;
  const std::array<IntPoint, 3>* corners = nullptr;  ///< its input triangle's grid corners
};

/// Not built yet: an uncut input triangle (see above).
inline bool unbuilt(const SoupPolygon& p) { return !p.poly; }
using Soup = std::vector<SoupPolygon>;

/// Recomputes the conservative box of a polygon from double approximations of
/// its exact vertices (an unbuilt triangle: its grid corners, exact in double).
/// |coord| < 2^26 so approx() errs by < 2^-26 units; the margin 2^-16 covers it
/// with room to spare.
void update_bounds(SoupPolygon& p);
/// The same conservative box for a built polygon.
void approx_bounds(const Polygon& poly, std::array<double, 3>& lo, std::array<double, 3>& hi);

/// The soup polygon for input triangle `c` (non-degenerate), unbuilt: its
/// box and a pointer to `c`, which must outlive it.
SoupPolygon unbuilt_triangle(const std::array<IntPoint, 3>& c, std::uint32_t id, std::uint32_t operand);

/// Builds an unbuilt triangle's edges and vertices (make_triangle of its
/// corners: the same polygon a built entry holds). No-op otherwise.
void materialize(SoupPolygon& p);

/// line_clearly_misses for a soup polygon, built or not (an unbuilt
/// triangle's corners are exact in double): the trace filter that lets most
/// unbuilt triangles a trace passes near stay unbuilt.
bool line_clearly_misses(const AxisLine& l, const std::array<double, 2>& uv, const SoupPolygon& p);

/// A soup's vertex approximations in one flat array, with each polygon's
/// normal signs: the filters of traces and of the leaf's gather read them
/// without chasing every polygon's buffers (a leaf tests each of its polygons
/// against every trace segment). Built or unbuilt polygons alike.
static_assert(kCoordLimit < (std::int64_t{1} << 53), "a grid coordinate is exact in double (SoupApprox::grid)");
struct SoupApprox {
  std::vector<std::array<double, 3>> verts;
  /// Per vertex: 1 if it is a grid point (stored_grid_point), whose
  /// approximation is then its exact coordinates (|x| <= 2^25): the exact
  /// tests of gather's undecided vertices (most of them shared with the
  /// polygon being cut) read it instead of the vertex, whose 120 bytes would
  /// be a cache miss each, in gather's hottest loop on a pile of slivers.
  std::vector<std::uint8_t> grid;
  std::vector<std::uint32_t> begin;                     ///< polygon i: verts[begin[i] .. begin[i+1])
  std::vector<std::array<std::int8_t, 3>> normal_sign;  ///< sign of each support normal coordinate
  double max_abs = 0;                                   ///< the largest |coordinate| in verts
  std::span<const std::array<double, 3>> of(std::size_t i) const {
    return {verts.data() + begin[i], verts.data() + begin[i + 1]};
  }
  std::span<const std::uint8_t> grid_of(std::size_t i) const {
    return {grid.data() + begin[i], grid.data() + begin[i + 1]};
  }
};
void approximate(const Soup& soup, SoupApprox& out);

/// classify's filter (point.hpp) with one error bound for all the vertices
/// of a SoupApprox: there |v - V/w| < 13u m, m = |a x~| + |b y~| + |c z~| +
/// |d~| summed in double; with every |coordinate| <= max_abs,
/// m <= (|a| + |b| + |c|) max_abs + |d~| (up to a few roundings, which the
/// bound's 2^-47 instead of classify's 2^-48 covers many times over). Per
/// vertex three products, three sums and a comparison, without classify's
/// sum of magnitudes; kUnsure where only the exact test can tell.
struct LeafPlaneFilter {
  LeafPlaneFilter(const PlaneApprox& p, double max_abs)
      : a(p.a),
        b(p.b),
        c(p.c),
        d(p.d),
        bound(((std::fabs(p.a) + std::fabs(p.b) + std::fabs(p.c)) * max_abs + std::fabs(p.d)) * 0x1p-47) {}
  static constexpr int kUnsure = 2;
  /// The sign of the plane at f (a vertex approximation with |f_k| <=
  /// max_abs), or kUnsure.
  int sign(const std::array<double, 3>& f) const {
    const double v = (a * f[0] + b * f[1]) + (c * f[2] + d);
    return v > bound ? 1 : (v < -bound ? -1 : kUnsure);
  }
  double a, b, c, d, bound;
};

/// line_clearly_misses for polygon i of the soup that `a` approximates: the
/// same answer as for the polygon itself, from the flat arrays.
bool line_clearly_misses(const AxisLine& l, const std::array<double, 2>& uv, const SoupApprox& a, std::size_t i);

/// The support plane of a polygon, built or not.
Plane support_of(const SoupPolygon& p);

/// p's polygon with edges and vertices: *p.poly, or, for an unbuilt
/// triangle, `scratch` filled with it (its buffers are reused across calls).
const Polygon& built_polygon(const SoupPolygon& p, Polygon& scratch);

/// The polygon's conservative box misses the box [lo, hi].
inline bool box_disjoint(const SoupPolygon& p, const std::array<double, 3>& lo, const std::array<double, 3>& hi) {
  return p.hi[0] < lo[0] || p.lo[0] > hi[0] || p.hi[1] < lo[1] || p.lo[1] > hi[1] || p.hi[2] < lo[2] || p.lo[2] > hi[2];
}

/// Closed integer box [lo, hi] per axis.
struct Box {
  std::array<std::int64_t, 3> lo{}, hi{};
};

/// A point with dyadic rational coordinates num[i] / 2^shift. Reference points
/// and trace paths use them: each coordinate is an axis plane (2^shift, -num)
/// whose coefficients stay inside the plane budget (2^shift <= 2^52 < 2^53,
/// |num| <= 2^(25+52) < 2^79), so every trace predicate is an ordinary
/// three-plane point classified against a plane. Fine shifts are only needed
/// to place a point inside a sliver; most points have shift <= 14.
struct Dyadic {
  std::array<__int128, 3> num{};
  int shift = 0;
};
inline constexpr int kMaxDyadicShift = 52;
static_assert(kMaxDyadicShift + 25 < OffsetCoef::bits && kMaxDyadicShift < NormalCoef::bits,
              "dyadic axis planes (2^shift, -num) must fit the plane budget: shift <= 52, |num| <= 2^77");

/// The same point with a finer common denominator 2^s (s >= p.shift).
Dyadic with_shift(const Dyadic& p, int s);
/// Exact comparison of coordinate i with an integer: -1, 0, +1.
int compare(const Dyadic& p, int axis, std::int64_t value);
/// Axis plane x_axis = p[axis], positive side above.
Plane dyadic_axis_plane(const Dyadic& p, int axis);
Point to_point(const Dyadic& p);
/// The axis-parallel line through p along `axis`.
AxisLine axis_line(const Dyadic& p, int axis);
double approx_coord(const Dyadic& p, int axis);

/// Winding-number vector: one entry per operand.
using Wnv = std::vector<int>;

}  // namespace ember::core
