// Convex polygon clipping (paper Section 4.2.1, Fig. 6).
#include "geometry/clip.hpp"

#include <array>
#include <vector>

namespace ember {
namespace {

/// Axis planes dominate the subdivision; their classify needs one 188-bit
/// product instead of four 241-bit ones. Returns the axis, or -1 if `s` is not
/// (+-e_axis, |d| <= kCoordLimit); `negate` tells whether s = -axis_plane(...).
int as_axis_plane(const Plane& s, std::int64_t& position, bool& negate) {
  const bool za = s.a.is_zero(), zb = s.b.is_zero(), zc = s.c.is_zero();
  int axis = -1;
  if (!za && zb && zc) axis = 0;
  if (za && !zb && zc) axis = 1;
  if (za && zb && !zc) axis = 2;
  if (axis < 0) return -1;
  const std::int64_t n = s.normal(axis).raw();
  if (n != 1 && n != -1) return -1;
  if (s.d > OffsetCoef(kCoordLimit) || s.d < OffsetCoef(-kCoordLimit)) return -1;
  negate = n < 0;
  // n*x + d = 0  <=>  x = -d/n = -n*d.
  const auto d = static_cast<std::int64_t>(s.d.raw());
  position = negate ? d : -d;
  return axis;
}

void push(Polygon& out, const Point& v, const Plane& e) {
  out.vertices.push_back(v);
  out.edges.push_back(e);
}

/// Assembles both parts from the vertex signs (Both case). `axis` >= 0 when the
/// split is an axis plane at `position` (up to orientation): the new vertices
/// then use the cheaper axis intersection; normalization makes the result
/// identical to intersect(support, edge, split).
ClipSide clip_impl(const Polygon& poly, std::span<const std::int8_t> signs, const Plane& split, int axis,
                   std::int64_t position, Polygon& negative_part, Polygon& positive_part) {
  const ClipSide side = clip_side(signs);
  if (side != ClipSide::Both) return side;

  const std::size_t n = poly.size();
  const Plane flipped = -split;
  negative_part.support = poly.support;
  positive_part.support = poly.support;
  // Each part has at most n + 1 corners (its own side's vertices, those on
  // the plane, and two new ones): reserving them once replaces the growth
  // steps of four vectors (most buffers are recycled and already that large).
  for (Polygon* part : {&negative_part, &positive_part}) {
    part->edges.clear();
    part->vertices.clear();
    part->edges.reserve(n + 1);
    part->vertices.reserve(n + 1);
  }

  for (std::size_t i = 0; i < n; ++i) {
    const std::size_t j = i + 1 == n ? 0 : i + 1;
    const int si = signs[i], sj = signs[j];
    const Point& v = poly.vertices[i];
    const Plane& e = poly.edges[i];
    // A vertex on the plane belongs to both parts; its outgoing edge becomes the
    // split plane in the part the original edge leaves.
    if (si <= 0) push(negative_part, v, (si == 0 && sj > 0) ? split : e);
    if (si >= 0) push(positive_part, v, (si == 0 && sj < 0) ? flipped : e);
    if (si * sj < 0) {
      // Edge i crosses the plane: new vertex support ∩ e ∩ split. Its normals are
      // independent because v_i and v_j lie strictly on opposite sides.
      Point x;
      if (axis >= 0) {
        detail::intersect_raw_axis(poly.support, e, axis, position, x);
      } else {
        detail::intersect_raw(poly.support, e, split, x);
      }
      detail::normalize_w(x);
      if (si < 0) {  // leaving the negative side
        push(negative_part, x, split);
        push(positive_part, x, e);
      } else {
        push(positive_part, x, flipped);
        push(negative_part, x, e);
      }
    }
  }
  return side;
}

}  // namespace

ClipSide clip(const Polygon& poly, const Plane& split, Polygon& negative_part, Polygon& positive_part) {
  const std::size_t n = poly.size();
  constexpr std::size_t kInline = 64;  // clipped convex polygons rarely exceed a few dozen vertices
  std::array<std::int8_t, kInline> inline_signs;
  std::vector<std::int8_t> heap_signs;
  std::int8_t* signs = inline_signs.data();
  if (n > kInline) {
    heap_signs.resize(n);
    signs = heap_signs.data();
  }
  std::int64_t position = 0;
  bool negate = false;
  const int axis = as_axis_plane(split, position, negate);
  for (std::size_t i = 0; i < n; ++i) {
    int s;
    if (axis >= 0) {
      s = classify_axis(poly.vertices[i], axis, position);
      if (negate) s = -s;
    } else {
      s = classify(poly.vertices[i], split);
    }
    signs[i] = static_cast<std::int8_t>(s);
  }
  return clip_impl(poly, std::span<const std::int8_t>(signs, n), split, axis, position, negative_part, positive_part);
}

ClipSide clip(const Polygon& poly, std::span<const std::int8_t> signs, const Plane& split, Polygon& negative_part,
              Polygon& positive_part) {
  std::int64_t position = 0;
  bool negate = false;
  const int axis = as_axis_plane(split, position, negate);
  return clip_impl(poly, signs, split, axis, position, negative_part, positive_part);
}

}  // namespace ember
