// Construction of plane-based convex polygons from grid points.
#include "geometry/polygon.hpp"

namespace ember {

bool assign_triangle(const IntPoint& p0, const IntPoint& p1, const IntPoint& p2, Polygon& out) {
  const std::optional<Plane> support = supporting_plane(p0, p1, p2);
  if (!support) return false;
  out.support = *support;
  // Assigning lists keeps the buffers' capacity: a reused polygon allocates nothing.
  out.edges = {edge_plane(p0, p1, *support), edge_plane(p1, p2, *support), edge_plane(p2, p0, *support)};
  // The grid points themselves are the vertices (w = 1): the same points as
  // support ∩ edges[i-1] ∩ edges[i], without the 188-bit intersection.
  out.vertices = {to_point(p0), to_point(p1), to_point(p2)};
  return true;
}

std::optional<Polygon> make_triangle(const IntPoint& p0, const IntPoint& p1, const IntPoint& p2) {
  Polygon poly;
  if (!assign_triangle(p0, p1, p2, poly)) return std::nullopt;
  return poly;
}

std::optional<Polygon> make_convex_polygon(std::span<const IntPoint> pts) {
  const std::size_t n = pts.size();
  for (const IntPoint& p : pts) detail::require_in_range(p);
  if (n < 3) return std::nullopt;
  // Strict convexity makes (p0, p1, p2) non-collinear and counter-clockwise, so
  // their plane is the support with the orientation of the input order.
  const std::optional<Plane> support = supporting_plane(pts[0], pts[1], pts[2]);
  if (!support) return std::nullopt;
  for (std::size_t i = 3; i < n; ++i)
    if (classify(pts[i], *support) != 0) return std::nullopt;  // not planar

  Polygon poly;
  poly.support = *support;
  poly.edges.reserve(n);
  poly.vertices.reserve(n);
  for (std::size_t i = 0; i < n; ++i) poly.edges.push_back(edge_plane(pts[i], pts[(i + 1) % n], *support));
  // Within the support, edge plane i cuts out the line of edge i. The polygon is
  // strictly convex and counter-clockwise iff every vertex not on edge i lies
  // strictly on its interior (negative) side; this also rejects repeated
  // vertices (zero edge planes), collinear runs, clockwise order and polygons
  // that wind more than once (star shapes). O(n^2), but only at input time.
  for (std::size_t i = 0; i < n; ++i) {
    for (std::size_t j = 0; j < n; ++j) {
      if (j == i || j == (i + 1) % n) continue;
      if (classify(pts[j], poly.edges[i]) >= 0) return std::nullopt;
    }
  }
  for (const IntPoint& p : pts) poly.vertices.push_back(to_point(p));
  return poly;
}

}  // namespace ember
