// Classification traces of the solid path (solid_trace.hpp).
#include "core/solid_trace.hpp"

#include "core/pieces.hpp"
#include "core/trace.hpp"

namespace ember::core {

namespace {

/// Calls visit(polygon, operand) for every triangle of an operand other than
/// `own` that the segment can meet (tree box query, then the triangle's box
/// and the line-miss filter), until visit returns false.
template <typename Visit>
bool for_each_met(const Tracer& tr, std::uint32_t own, const AxisSegment& seg, TraceScratch& sc, Visit&& visit) {
  const Box32 query = enclosing_box(seg.lo, seg.hi);
  bool ok = true;
  for (std::size_t o = 0; o < tr.operands && ok; ++o) {
    if (o == own) continue;  // solid: its winding numbers at f are known
    tr.trees.tree[o].for_each_overlapping(query, [&](std::uint32_t item) {
      if (!ok) return;
      const SoupPolygon& p = tr.soup[tr.trees.begin[o] + item];
      if (box_disjoint(p, seg.lo, seg.hi) || line_clearly_misses(seg.line, seg.uv, p)) return;
      ok = visit(built_polygon(p, sc.built), p.operand);
    });
  }
  return ok;
}

/// The last segment, from `start` along k onto x on S (pieces.hpp):
/// crossings into w, transitions at x into delta; `side` is start's side of S.
bool trace_onto(const Tracer& tr, std::uint32_t own, const Plane& S, const Dyadic& start, int k, const AxisPoint& x,
                Wnv& w, Wnv& delta, int& side, TraceScratch& sc) {
  AxisSegment seg;
  if (!onto_segment(S, start, k, x, seg, side)) return false;
  delta.assign(tr.operands, 0);
  return for_each_met(tr, own, seg, sc,
                      [&](const Polygon& p, std::uint32_t o) { return meet_onto(seg, p, o, S, x, w, delta); });
}

/// w holds the region beside x on `side` of S, delta the transitions at x.
void finish(int side, std::uint32_t own, const Wnv& w, const Wnv& delta, Wnv& w_front, Wnv& w_back) {
  w_front = w;
  w_back = w;
  for (std::size_t o = 0; o < w.size(); ++o) (side > 0 ? w_back[o] += delta[o] : w_front[o] -= delta[o]);
  w_front[own] = 0;
  w_back[own] = 1;
}

}  // namespace

bool classify_from_outside(const Tracer& tr, const Polygon& f, std::uint32_t own, std::uint64_t seed, Wnv& w_front,
                           Wnv& w_back, TraceScratch& sc) {
  const Plane& S = f.support;
  const int k = dominant_axis(S);
  const Dyadic base;  // only its shift (0) matters: the start's coordinate k is set below
  return for_each_interior_target(f, base, seed, [&](const Dyadic& target, const AxisPoint& x, int variant) {
    const double xk = approx(x)[k];
    const bool low_nearer = xk - static_cast<double>(tr.box.lo[k]) <= static_cast<double>(tr.box.hi[k]) - xk;
    Dyadic start = target;
    start.num[k] = static_cast<__int128>((low_nearer == (variant == 0)) ? tr.box.lo[k] : tr.box.hi[k]) << target.shift;
    sc.w.assign(tr.operands, 0);  // outside the root box: outside everything
    int side = 0;
    if (!trace_onto(tr, own, S, start, k, x, sc.w, sc.delta, side, sc)) return false;
    finish(side, own, sc.w, sc.delta, w_front, w_back);
    return true;
  });
}

}  // namespace ember::core
