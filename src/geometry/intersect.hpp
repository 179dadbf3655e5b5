#pragma once
// Line / segment versus convex polygon (paper Section 3.1, Fig. 2). A line is a
// pair of non-parallel planes (l0, l1); a segment adds two bounding planes
// (r0, r1) and consists of the line points with classify(r0) <= 0 and
// classify(r1) <= 0.
#include "geometry/polygon.hpp"

namespace ember {

enum class LineHit {
  Miss,      ///< no common point (also: line parallel to the support, off it)
  Interior,  ///< the line meets the polygon strictly inside
  Boundary,  ///< the line meets the polygon on an edge or at a vertex
  InPlane,   ///< the line lies in the support plane (overlap with the polygon NOT decided)
};

/// Intersects the line (l0, l1) with `poly`. When the result is Interior or
/// Boundary and `hit` is non-null, *hit receives the intersection point
/// intersect(l0, l1, poly.support); otherwise *hit is left untouched.
/// InPlane is reported whenever the line lies in the support plane, whether or
/// not it overlaps the polygon: callers treat it as a degenerate configuration.
LineHit intersect_line(const Plane& l0, const Plane& l1, const Polygon& poly, Point* hit);

struct SegmentHit {
  LineHit kind;
  /// The intersection point lies on r0 or r1 (only set when kind is Interior or Boundary).
  bool at_endpoint;
};

/// Intersects the segment (l0, l1; r0, r1) with `poly`: like intersect_line, but
/// Miss when the line point classifies > 0 on r0 or r1. at_endpoint reports a
/// point classifying 0 on r0 or r1. InPlane is reported for a line in the support
/// plane regardless of the segment bounds. *hit is written as in intersect_line.
SegmentHit intersect_segment(const Plane& l0, const Plane& l1, const Plane& r0, const Plane& r1, const Polygon& poly,
                             Point* hit);

}  // namespace ember
