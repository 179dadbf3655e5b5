#pragma once
// Convex polygons in plane-based form (paper Fig. 2): a supporting plane plus
// one edge plane per edge, with cached homogeneous vertices.
//
// Conventions (docs/geometry.md):
//  * edge i runs from vertex i to vertex i+1 (cyclic);
//  * vertex i = support ∩ edges[i-1] ∩ edges[i] (indices modulo n);
//  * the interior lies on the NEGATIVE side of every edge plane;
//  * seen from the positive side of the support, vertices are counter-clockwise.
#include <optional>
#include <span>
#include <vector>

#if EMBER_SCALABLE_ALLOCATOR
#include <tbb/scalable_allocator.h>
#endif

#include "geometry/plane.hpp"
#include "geometry/point.hpp"

namespace ember {

/// Storage of a polygon's edges and vertices. The Boolean creates and frees
/// millions of these small buffers from all worker threads; oneTBB's scalable
/// allocator (thread-local pools) serves them several times faster than the
/// default heap. Sanitizer builds keep std::allocator so ASan sees every buffer.
#if EMBER_SCALABLE_ALLOCATOR
template <typename T>
using PolygonBuffer = std::vector<T, tbb::scalable_allocator<T>>;
#else
template <typename T>
using PolygonBuffer = std::vector<T>;
#endif

struct Polygon {
  Plane support;
  PolygonBuffer<Plane> edges;
  PolygonBuffer<Point> vertices;

  std::size_t size() const { return vertices.size(); }
};

/// Triangle p0, p1, p2 (counter-clockwise around its supporting plane's normal).
/// nullopt if the points are collinear. Vertices are stored with w = 1.
/// Throws ember::Error if a coordinate exceeds kCoordLimit.
std::optional<Polygon> make_triangle(const IntPoint& p0, const IntPoint& p1, const IntPoint& p2);
/// make_triangle into an existing polygon, reusing its buffers. False (and
/// `out` unspecified) if the points are collinear.
bool assign_triangle(const IntPoint& p0, const IntPoint& p1, const IntPoint& p2, Polygon& out);

/// Planar, strictly convex polygon (no repeated or collinear consecutive
/// vertices, turning once). nullopt unless all of that holds (decided exactly).
/// The support is taken through the first three vertices, so the orientation of
/// the input order defines the normal. Throws ember::Error if a coordinate
/// exceeds kCoordLimit.
std::optional<Polygon> make_convex_polygon(std::span<const IntPoint> pts);

/// For a point ON the support plane: -1 strictly inside, 0 on the boundary
/// (an edge or vertex), +1 outside. Exact.
template <typename P>  // Point or AxisPoint: anything classify() accepts
int locate(const Polygon& poly, const P& pt) {
  int worst = -1;
  for (const Plane& e : poly.edges) {
    const int s = classify(pt, e);
    if (s > 0) return 1;
    if (s == 0) worst = 0;
  }
  return worst;
}

}  // namespace ember
