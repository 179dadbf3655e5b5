// Line / segment versus convex polygon (paper Section 3.1).
#include "geometry/intersect.hpp"

namespace ember {
namespace {

/// Intersection of the line with the support. Returns Miss (parallel, off the
/// plane) or InPlane when w = 0, Interior otherwise (point in `x`, w > 0).
LineHit line_point(const Plane& l0, const Plane& l1, const Plane& support, Point& x) {
  if (!detail::intersect_raw(l0, l1, support, x)) {
    // w = 0: the normals are dependent. All of x, y, z vanish too iff the support
    // is a combination of l0 and l1 (rank 2), i.e. the line lies in it.
    return (x.x.is_zero() && x.y.is_zero() && x.z.is_zero()) ? LineHit::InPlane : LineHit::Miss;
  }
  detail::normalize_w(x);
  return LineHit::Interior;
}

LineHit against_polygon(const Polygon& poly, const Point& x, Point* hit) {
  const int loc = locate(poly, x);
  if (loc > 0) return LineHit::Miss;
  if (hit) *hit = x;
  return loc == 0 ? LineHit::Boundary : LineHit::Interior;
}

}  // namespace

LineHit intersect_line(const Plane& l0, const Plane& l1, const Polygon& poly, Point* hit) {
  Point x;
  const LineHit k = line_point(l0, l1, poly.support, x);
  if (k != LineHit::Interior) return k;
  return against_polygon(poly, x, hit);
}

SegmentHit intersect_segment(const Plane& l0, const Plane& l1, const Plane& r0, const Plane& r1, const Polygon& poly,
                             Point* hit) {
  Point x;
  const LineHit k = line_point(l0, l1, poly.support, x);
  if (k != LineHit::Interior) return {k, false};
  const int c0 = classify(x, r0), c1 = classify(x, r1);
  if (c0 > 0 || c1 > 0) return {LineHit::Miss, false};
  const LineHit kind = against_polygon(poly, x, hit);
  return {kind, kind != LineHit::Miss && (c0 == 0 || c1 == 0)};
}

}  // namespace ember
