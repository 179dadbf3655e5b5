// Classification traces of the solid path (solid_trace.hpp).
#include "core/route/solid/solid_trace.hpp"

#include "core/route/shared/pieces.hpp"
#include "core/route/shared/trace.hpp"

namespace ember::core {

namespace {

/// Calls visit(polygon, operand) for every triangle of operand `operand`'s
/// `tree` that the segment can meet (tree box query, then the triangle's
/// box and the line-miss filter), until visit returns false (false then).
/// Tree item i is grid triangle first + i: seen as the root soup's unbuilt
/// polygon for it, the same box and filters (the soup itself is not built
/// on the solid path, root_problem.hpp).
template <typename Visit>
bool for_each_met_in(std::span<const std::array<IntPoint, 3>> corners, const TriangleTree& tree, std::uint32_t first,
                     std::uint32_t operand, const AxisSegment& seg, const Box32& query, TraceScratch& sc,
                     Visit& visit) {
  bool ok = true;
  tree.for_each_overlapping(query, [&](std::uint32_t item) {
    if (!ok) return;
    const SoupPolygon p = unbuilt_triangle(corners[first + item], first + item, operand);
    if (box_disjoint(p, seg.lo, seg.hi) || line_clearly_misses(seg.line, seg.uv, p)) return;
    ok = visit(built_polygon(p, sc.built), operand);
  });
  return ok;
}

/// The last segment, from `start` along k onto x on S (pieces.hpp):
/// crossings into w, transitions at x into delta; `side` is start's side of
/// S. `met(seg, visit)` runs visit on the triangles the segment can meet.
template <typename Met>
bool trace_onto(std::size_t operands, const Plane& S, const Dyadic& start, int k, const AxisPoint& x, Wnv& w,
                Wnv& delta, int& side, Met&& met) {
  AxisSegment seg;
  if (!onto_segment(S, start, k, x, seg, side)) return false;
  delta.assign(operands, 0);
  return met(seg, [&](const Polygon& p, std::uint32_t o) { return meet_onto(seg, p, o, S, x, w, delta); });
}

/// Traces from outside the root box onto piece f (see the header): the
/// winding numbers just in front of and behind f of the operands whose
/// triangles `met` visits, the others' left 0.
template <typename Met>
bool trace_from_outside(const Box& box, std::size_t operands, const Polygon& f, std::uint64_t seed, Wnv& w_front,
                        Wnv& w_back, TraceScratch& sc, Met&& met) {
  const Plane& S = f.support;
  const int k = dominant_axis(S);
  const Dyadic base;  // only its shift (0) matters: the start's coordinate k is set below
  return for_each_interior_target(f, base, seed, [&](const Dyadic& target, const AxisPoint& x, int variant) {
    const double xk = approx(x)[k];
    const bool low_nearer = xk - static_cast<double>(box.lo[k]) <= static_cast<double>(box.hi[k]) - xk;
    Dyadic start = target;
    start.num[k] = static_cast<__int128>((low_nearer == (variant == 0)) ? box.lo[k] : box.hi[k]) << target.shift;
    sc.w.assign(operands, 0);  // outside the root box: outside everything
    int side = 0;
    if (!trace_onto(operands, S, start, k, x, sc.w, sc.delta, side, met)) return false;
    // w holds the region beside x on `side` of S, delta the transitions at x.
    w_front = sc.w;
    w_back = sc.w;
    for (std::size_t o = 0; o < operands; ++o) (side > 0 ? w_back[o] += sc.delta[o] : w_front[o] -= sc.delta[o]);
    return true;
  });
}

}  // namespace

bool classify_from_outside(const Tracer& tr, const Polygon& f, std::uint32_t own, std::uint64_t seed, Wnv& w_front,
                           Wnv& w_back, TraceScratch& sc) {
  // Every operand's triangles but own's: own is solid, its winding numbers at f are known.
  const auto met = [&](const AxisSegment& seg, auto&& visit) {
    const Box32 query = enclosing_box(seg.lo, seg.hi);
    for (std::size_t o = 0; o < tr.operands; ++o)
      if (o != own && !for_each_met_in(tr.corners, tr.trees.tree[o], tr.trees.begin[o], static_cast<std::uint32_t>(o),
                                       seg, query, sc, visit))
        return false;
    return true;
  };
  if (!trace_from_outside(tr.box, tr.operands, f, seed, w_front, w_back, sc, met)) return false;
  w_front[own] = 0;
  w_back[own] = 1;
  return true;
}

bool own_winding_from_outside(std::span<const std::array<IntPoint, 3>> corners, const TriangleTree& tree,
                              std::uint32_t first, const Box& box, std::size_t operands, const Polygon& f,
                              std::uint32_t own, std::uint64_t seed, int& front, int& back, TraceScratch& sc) {
  const auto met = [&](const AxisSegment& seg, auto&& visit) {
    return for_each_met_in(corners, tree, first, own, seg, enclosing_box(seg.lo, seg.hi), sc, visit);
  };
  Wnv w_front, w_back;
  if (!trace_from_outside(box, operands, f, seed, w_front, w_back, sc, met)) return false;
  front = w_front[own];
  back = w_back[own];
  return true;
}

}  // namespace ember::core
