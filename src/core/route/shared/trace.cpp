#include "core/route/shared/trace.hpp"

#include <algorithm>
#include <optional>
#include <vector>

namespace ember::core {

namespace {

struct Candidate {
  Point point;
  std::size_t plane;  // index of the constraint whose plane cuts the line here
};

/// The points where the line meets each transverse constraint's plane and that
/// satisfy every constraint. The feasible part of the line is a closed
/// interval (convex, bounded by a transverse constraint on each side), so it
/// is non-empty iff it has an end point, and each end point is one of these.
std::vector<Candidate> feasible_ends(const Plane& l0, const Plane& l1, std::span<const Plane> constraints) {
  std::vector<Candidate> out;
  for (std::size_t i = 0; i < constraints.size(); ++i) {
    const std::optional<Point> x = intersect(l0, l1, constraints[i]);
    if (!x) continue;  // parallel to the line: checked through the other points
    bool ok = true;
    for (std::size_t j = 0; j < constraints.size() && ok; ++j)
      if (j != i && classify(*x, constraints[j]) > 0) ok = false;
    if (ok) out.push_back({*x, i});
  }
  return out;
}

}  // namespace

bool line_region_nonempty(const Plane& l0, const Plane& l1, std::span<const Plane> constraints) {
  return !feasible_ends(l0, l1, constraints).empty();
}

bool line_region_has_length(const Plane& l0, const Plane& l1, std::span<const Plane> constraints) {
  const std::vector<Candidate> ends = feasible_ends(l0, l1, constraints);
  // Two feasible end points are distinct iff one is off the other's plane.
  for (std::size_t i = 0; i < ends.size(); ++i)
    for (std::size_t j = i + 1; j < ends.size(); ++j)
      if (classify(ends[i].point, constraints[ends[j].plane]) != 0) return true;
  return false;
}

bool make_axis_segment(const Dyadic& a, const Dyadic& b, int axis, AxisSegment& seg) {
  const int dir = a.num[axis] < b.num[axis] ? 1 : (a.num[axis] > b.num[axis] ? -1 : 0);
  if (dir == 0) return false;
  const int u = (axis + 1) % 3, v = (axis + 2) % 3;
  const AxisLine line = axis_line(a, axis);
  // Segment = points of the line with r0 <= 0 and r1 <= 0.
  const Plane pa = dyadic_axis_plane(a, axis), pb = dyadic_axis_plane(b, axis);
  seg = AxisSegment{
      line, dyadic_axis_plane(a, u), dyadic_axis_plane(a, v), dir > 0 ? -pa : pa, dir > 0 ? pb : -pb, dir, {},
      {},   line_point_approx(line)};
  for (int i = 0; i < 3; ++i) {
    seg.lo[i] = std::min(approx_coord(a, i), approx_coord(b, i));
    seg.hi[i] = std::max(approx_coord(a, i), approx_coord(b, i));
  }
  return true;
}

bool trace_axis_segment(const Soup& soup, const Dyadic& a, const Dyadic& b, int axis, Wnv& w, std::uint32_t skip,
                        const SoupApprox* flat) {
  AxisSegment seg;
  if (!make_axis_segment(a, b, axis, seg)) return true;
  // The filters here, before the call: most polygons of a leaf miss the
  // segment's box. One loop per kind of miss filter; scan_soup shares a root
  // soup's (the proof's) among the threads.
  const SoupPolygon* const polys = soup.data();  // not reloaded after each write to w
  Wnv no_delta;
  const auto run = [&](auto&& clearly_misses) {
    return scan_soup(soup.size(), w, no_delta, [&](std::size_t i, Wnv& sum, Wnv&, Polygon& built) {
      const SoupPolygon& p = polys[i];
      if (p.operand == skip || box_disjoint(p, seg.lo, seg.hi) || clearly_misses(i, p)) return true;
      return add_crossing(seg, built_polygon(p, built), p.operand, sum);
    });
  };
  if (flat)
    return run([&](std::size_t i, const SoupPolygon&) { return line_clearly_misses(seg.line, seg.uv, *flat, i); });
  return run([&](std::size_t, const SoupPolygon& p) { return line_clearly_misses(seg.line, seg.uv, p); });
}

bool add_crossing(const AxisSegment& s, const SoupPolygon& p, Wnv& w) {
  Polygon scratch;
  return add_crossing(s, built_polygon(p, scratch), p.operand, w);
}

bool add_crossing(const AxisSegment& s, const Polygon& poly, std::uint32_t operand, Wnv& w) {
  const SegmentHit h = intersect_segment(s.line, s.r0, s.r1, poly);
  switch (h.kind) {
    case LineHit::Miss: return true;
    case LineHit::Boundary: return false;
    case LineHit::Interior:
      if (h.at_endpoint) return false;
      // Crossing along +axis through a polygon whose normal points along
      // +axis goes from its back to its front: w drops by its transition.
      w[operand] -= s.dir * poly.support.normal(s.line.axis).sign();
      return true;
    case LineHit::InPlane: {
      std::vector<Plane> cons;
      cons.reserve(poly.edges.size() + 2);
      cons.push_back(s.r0);
      cons.push_back(s.r1);
      cons.insert(cons.end(), poly.edges.begin(), poly.edges.end());
      return !line_region_nonempty(s.l0, s.l1, cons);
    }
  }
  return true;
}

bool trace_path(const Soup& soup, const Dyadic& a, const Dyadic& b, const std::array<int, 3>& order, Wnv& w,
                std::uint32_t skip, const SoupApprox* flat) {
  const int s = std::max(a.shift, b.shift);
  Dyadic cur = with_shift(a, s);
  const Dyadic end = with_shift(b, s);
  for (const int axis : order) {
    if (cur.num[axis] == end.num[axis]) continue;
    Dyadic next = cur;
    next.num[axis] = end.num[axis];
    if (!trace_axis_segment(soup, cur, next, axis, w, skip, flat)) return false;
    cur = next;
  }
  return true;
}

}  // namespace ember::core
