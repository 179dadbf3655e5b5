// Leaf computation (paper Sections 4.3 and 4.4): every polygon is cut by all
// others with a polygon-local BSP, then each enabled piece is classified by
// tracing a path from the leaf's reference point to an interior point.
#include "core/route/general/leaf.hpp"

#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <iterator>
#include <numeric>
#include <span>

#include "core/route/shared/edge_windings.hpp"
#include "core/route/general/frame_boxes.hpp"
#include "core/route/shared/pieces.hpp"
#include "core/model/output_polygon.hpp"
#include "core/model/solve_context.hpp"
#include "core/route/general/subproblem.hpp"
#include "core/route/general/subdivide.hpp"
#include "core/route/shared/trace.hpp"
#include "ember/error.hpp"

namespace ember::core {

namespace {

bool boxes_overlap(const SoupPolygon& a, const SoupPolygon& b) { return !box_disjoint(a, b.lo, b.hi); }

/// Buffers reused across the polygons of a leaf (allocation-free inner loops).
struct LeafScratch {
  std::vector<std::int8_t> other_signs, signs;
  std::vector<std::int8_t> t_signs;  ///< gather, pile leaves: t's vertices against a candidate's plane
  std::vector<Plane> cons;
  Wnv w, delta;
  std::vector<std::uint32_t> related;      ///< soup indices of the polygons that touch t's plane near t
  std::vector<std::uint32_t> related_at;   ///< per related polygon: its signs in related_signs (coplanar: none)
  std::vector<std::int8_t> related_signs;  ///< vertex signs against t's plane, concatenated
  std::vector<std::uint32_t> free_front, free_back;  ///< per operand: == stamp if free on that side of t
  std::uint32_t stamp = 0;
  std::size_t n_front = 0, n_back = 0;  ///< free operands per side
  std::vector<Piece> sub, next;         ///< refinement of one piece; pieces being rebuilt
  Polygon neg, pos;                     ///< clip outputs (a cut's old piece hands its buffers on)
  /// Pile leaves only (null elsewhere): the leaf soup's approximations
  /// (soup.hpp) for the filters of gather and of the traces, and boxes in the
  /// leaf's principal frame (frame_boxes.hpp), which separate slivers that all
  /// share one axis-aligned box. Shared by the threads of the leaf.
  const SoupApprox* approx = nullptr;
  const FrameBoxes* frame = nullptr;
  FrameBoxes::Query frame_query;
  FrameBoxes::Candidates candidates;  ///< the frame boxes' answer for t
};

/// touches_plane(poly, plane, approx, signs) for a polygon whose vertex
/// approximations (each vertex's f, in order: SoupApprox) are `verts`, with
/// the same signs and answer: a floating-point filter on every vertex first
/// (LeafPlaneFilter: classify's, with one bound for the leaf), and
/// the exact test only for the vertices it cannot place, none at all when
/// the filter puts every vertex strictly on one side (most polygons a pile
/// leaf's frame grid offers), so that no vertex is filtered twice, as it
/// would be by filtering first and then calling touches_plane, which filters
/// again. Inlined into gather's two calls: a pile of slivers calls it for
/// every candidate, and a call's prologue and epilogue would be a large part
/// of the filter's cost.
[[gnu::always_inline]] inline bool touches_plane_filtered(std::span<const std::array<double, 3>> verts,
                                                          std::span<const std::uint8_t> grid, const SoupPolygon& o,
                                                          const Plane& plane, const LeafPlaneFilter& filter,
                                                          std::vector<std::int8_t>& signs) {
  constexpr int kUnsure = LeafPlaneFilter::kUnsure;
  const std::size_t n = verts.size();
  signs.resize(n);
  bool unsure = false, neg = false, pos = false;
  for (std::size_t v = 0; v < n; ++v) {
    const int s = filter.sign(verts[v]);
    signs[v] = static_cast<std::int8_t>(s);
    unsure |= s == kUnsure;
    neg |= s < 0;
    pos |= s == 1;
  }
  if (!unsure) return neg && pos;  // the filter never answers 0
  bool zero = false;
  for (std::size_t v = 0; v < n; ++v) {
    if (signs[v] != kUnsure) continue;
    // A grid point's approximation is exact: the integer test without
    // reading the vertex (SoupApprox::grid).
    const std::array<double, 3>& f = verts[v];
    const int s = grid[v] ? classify(IntPoint{static_cast<std::int64_t>(f[0]), static_cast<std::int64_t>(f[1]),
                                              static_cast<std::int64_t>(f[2])},
                                     plane)
                          : classify_exact(o.poly->vertices[v], plane);
    signs[v] = static_cast<std::int8_t>(s);
    zero |= s == 0;
    neg |= s < 0;
    pos |= s > 0;
  }
  return zero || (neg && pos);
}

/// False only when polygon o meets the closed polygon t in at most one
/// point: then o cuts no piece of t, holds no stretch of an edge of t
/// (edge_windings.hpp), and changes no winding number just beside t except
/// at that point, so leaving it out of `related` changes no cut and narrows
/// the free operands to the exact ones. `o_signs` are o's vertices' exact
/// sides of t's plane (touching or straddling it; not coplanar). Where one
/// of the two touches the other's plane without crossing it, its chord on
/// the common line is empty or one vertex, unless two of its vertices lie
/// there (an edge in the other's plane: kept, untested).
/// In a pile of slivers nearly all the polygons that touch t's plane within
/// t's box meet t in at most a point (most of them share one vertex with
/// it: the end fans of rods); as `related` they would make every operand
/// free on both sides of t, ruling out the piece-level early termination,
/// and each would be tried as a cut of every piece.
bool may_share_a_stretch(const Polygon& t, const Polygon& o, const std::vector<std::int8_t>& o_signs,
                         std::vector<std::int8_t>& t_signs, std::vector<Plane>& cons) {
  const Sides os = sides_of(o_signs);
  if (!os.straddles()) return os.on >= 2;
  const Sides ts = classify_vertices(t, o.support, t_signs);
  if (!ts.straddles()) return ts.on >= 2;
  return chords_overlap(t, t.support, t_signs, o, o_signs, cons);
}

/// True if t lies in a face plane of the box: then one side of t is outside
/// the box, where the soup does not show which polygons touch t.
bool on_box_face(const SoupPolygon& t, const Box& box) {
  const Plane& S = t.poly->support;
  for (int a = 0; a < 3; ++a) {
    if (S.normal((a + 1) % 3).sign() != 0 || S.normal((a + 2) % 3).sign() != 0) continue;
    const Point& v = t.poly->vertices.front();
    return classify(v, axis_plane(a, box.lo[a])) == 0 || classify(v, axis_plane(a, box.hi[a])) == 0;
  }
  return false;
}

/// One pass over the soup for polygon t: collects the polygons that can cut t
/// (they touch t's plane within t's box) and, per side of t, the operands
/// whose winding number may change along that side of t ("free"). Just in
/// front of t, w changes only across polygons that touch t's plane and reach
/// in front of it; a coplanar polygon of a closed operand changes nothing by
/// itself (its edges continue into polygons that leave the plane, which are
/// counted). Coplanar polygons of open operands count on both sides.
/// `direction[i]` names polygon i's class of parallel planes.
void gather(const Soup& soup, const SoupPolygon& t, const SolveContext& ctx,
            const std::vector<std::uint32_t>& direction, LeafScratch& sc) {
  const auto t_index = static_cast<std::size_t>(&t - soup.data());
  const std::uint32_t t_direction = direction[t_index];
  const bool t_solid = ctx.solid[t.operand] != 0;
  const PlaneApprox t_approx(t.poly->support);
  const LeafPlaneFilter t_filter(t_approx, sc.approx ? sc.approx->max_abs : 0);
  sc.related.clear();
  sc.related_at.clear();
  sc.related_signs.clear();
  if (sc.free_front.size() != ctx.operands) {
    sc.free_front.assign(ctx.operands, 0);
    sc.free_back.assign(ctx.operands, 0);
    sc.stamp = 0;
  }
  ++sc.stamp;
  sc.n_front = sc.n_back = 0;
  const auto mark = [&](std::vector<std::uint32_t>& f, std::size_t& n, std::uint32_t o) {
    if (f[o] != sc.stamp) {
      f[o] = sc.stamp;
      ++n;
    }
  };
  const SoupPolygon* const polys = soup.data();  // not reloaded after each push_back
  const auto consider = [&](std::size_t i) {
    const SoupPolygon& o = polys[i];
    // In a pile leaf, a polygon on a plane not parallel to t's is first
    // tested against t's plane from the flat approximations, without reading
    // its soup entry (a cache miss each: most candidates the frame grid
    // offers stop here).
    const bool parallel = direction[i] == t_direction;
    const bool plane_first = sc.approx && !parallel;
    if (plane_first &&
        !touches_plane_filtered(sc.approx->of(i), sc.approx->grid_of(i), o, t.poly->support, t_filter, sc.other_signs))
      return;
    // Two polygons of one solid operand never cross or overlap (NSI), and the
    // solid operand's own winding numbers at t are known (0 / 1). (Checked
    // before the boxes: it is cheaper and skips half of a two-solid leaf.)
    if ((o.operand == t.operand && t_solid) || o.id == t.id || !boxes_overlap(t, o)) return;
    bool front = false, back = false;
    // Coplanar first: one plane comparison instead of exact zero tests of
    // every vertex (stacks are full of them).
    if (!parallel || !coplanar(t.poly->support, o.poly->support)) {
      if (!plane_first && !(sc.approx ? touches_plane_filtered(sc.approx->of(i), sc.approx->grid_of(i), o,
                                                               t.poly->support, t_filter, sc.other_signs)
                                      : touches_plane(*o.poly, t.poly->support, t_approx, sc.other_signs)))
        return;
      // Pile leaves only: elsewhere few polygons get here, and most of
      // those meet t.
      if (sc.approx && !may_share_a_stretch(*t.poly, *o.poly, sc.other_signs, sc.t_signs, sc.cons)) return;
      for (const std::int8_t v : sc.other_signs) {
        front |= v > 0;
        back |= v < 0;
      }
    }
    sc.related.push_back(static_cast<std::uint32_t>(i));
    sc.related_at.push_back(static_cast<std::uint32_t>(sc.related_signs.size()));
    if (front || back) sc.related_signs.insert(sc.related_signs.end(), sc.other_signs.begin(), sc.other_signs.end());
    if (!front && !back && !ctx.closed[o.operand]) front = back = true;  // coplanar, open operand
    if (front) mark(sc.free_front, sc.n_front, o.operand);
    if (back) mark(sc.free_back, sc.n_back, o.operand);
  };
  // In a pile leaf the frame grid names the few polygons that can touch t, or
  // a scan of all frame boxes does (for a polygon wide across the grid, or in
  // a leaf whose grid is coarse: FrameBoxes::candidates), either in ascending
  // order, as the full scan would visit them. The others' frame boxes are
  // apart from t's: they cannot touch t, so they change nothing just beside
  // t and cut nothing, and leaving them out only narrows the free operands
  // to the exact ones.
  if (sc.frame) {
    sc.frame->candidates(t_index, sc.frame_query, sc.candidates);
    for (const std::uint32_t i : sc.candidates) consider(i);
    return;
  }
  for (std::size_t i = 0, n = soup.size(); i < n; ++i) consider(i);
}

/// Starts t's pieces: t minus every coplanar polygon with a lower id, which
/// represents the overlap (Fig. 8). Only enabled pieces are kept, and the
/// loop stops as soon as t is covered: in a coplanar stack most polygons are
/// covered by their first few lower-id neighbours.
/// `parallel` holds t's class of parallel polygons (soup indices, ascending)
/// and `at` t's position in it: only those can be coplanar with t.
/// Returns true if no such polygon overlapped t (then pieces = {t}).
bool disable_covered(const Soup& soup, const SoupPolygon& t, const SolveContext& ctx,
                     std::span<const std::uint32_t> parallel, std::size_t at, LeafScratch& sc,
                     std::vector<Piece>& pieces) {
  pieces.resize(1);
  pieces[0].poly = *t.poly;  // reuses the capacity of the previous polygon's first piece
  std::vector<Piece>& next = sc.next;
  Polygon neg, pos;
  // Nearest lower ids first: in a stack, t's predecessors (its own face's
  // other triangle, the previous copy) usually cover it after one or two cuts.
  // What is left of t shrinks as it is cut: polygons outside the box of the
  // remaining pieces are skipped without a plane test.
  std::array<double, 3> lo = t.lo, hi = t.hi;
  bool cut = false, untouched = true;
  for (std::size_t k = parallel.size(); k-- > 0;) {
    if (k == at) continue;
    const SoupPolygon& o = soup[parallel[k]];
    if (o.id >= t.id || box_disjoint(o, lo, hi)) continue;
    if (o.operand == t.operand && ctx.solid[t.operand]) continue;  // NSI: no overlap
    if (!coplanar(t.poly->support, o.poly->support)) continue;
    next.clear();
    cut = false;
    for (Piece& p : pieces) {
      if (!coplanar_overlap(p.poly, *o.poly)) {
        next.push_back(std::move(p));
        continue;
      }
      // The parts outside o stay; the part inside o is o's to emit.
      for (const Plane& e : o.poly->edges) {
        if (clip(p.poly, e, neg, pos) != ClipSide::Both) continue;
        next.push_back({std::move(pos)});
        std::swap(p.poly, neg);
      }
      cut = true;
    }
    std::swap(pieces, next);
    if (pieces.empty()) return false;
    if (cut) {
      untouched = false;
      constexpr double kMargin = 1.0 / 65536;  // as update_bounds: covers the approximation error
      lo = {HUGE_VAL, HUGE_VAL, HUGE_VAL};
      hi = {-HUGE_VAL, -HUGE_VAL, -HUGE_VAL};
      for (const Piece& p : pieces)
        for (const Point& v : p.poly.vertices)
          for (int a = 0; a < 3; ++a) {
            lo[a] = std::min(lo[a], approx(v)[a] - kMargin);
            hi[a] = std::max(hi[a], approx(v)[a] + kMargin);
          }
    }
  }
  return untouched;
}

/// Refines `pieces` (enabled pieces of t, already outside every lower-id
/// coplanar polygon) until no other polygon crosses a piece's interior: C3
/// cuts along transverse polygons and, where they can matter, C4 cuts along
/// higher-id coplanar polygons' edges. Those cuts are needed only for open
/// operands or when t lies in a box face (a closed operand's coplanar edge
/// continues into a polygon leaving the plane, whose C3 cut is made anyway,
/// unless that polygon lies outside the box).
void refine(const Soup& soup, const SoupPolygon& t, const SolveContext& ctx, bool face, LeafScratch& sc,
            std::vector<Piece>& pieces) {
  for (std::size_t k = 0; k < sc.related.size(); ++k) {
    const SoupPolygon& o = soup[sc.related[k]];
    const std::size_t at = sc.related_at[k];
    const std::size_t end = k + 1 < sc.related.size() ? sc.related_at[k + 1] : sc.related_signs.size();
    if (at == end) {  // coplanar (a touching polygon has a vertex off the plane)
      if (o.id < t.id || (ctx.closed[o.operand] && !face)) continue;
      const std::size_t n = pieces.size();
      for (std::size_t i = 0; i < n; ++i)
        if (coplanar_overlap(pieces[i].poly, *o.poly)) cut_by_coplanar(pieces, i, *o.poly, sc.neg, sc.pos);
    } else {
      sc.other_signs.assign(sc.related_signs.begin() + at, sc.related_signs.begin() + end);
      const std::size_t n = pieces.size();
      for (std::size_t i = 0; i < n; ++i)
        cut_by_transverse(pieces, i, t.poly->support, *o.poly, sc.other_signs, sc.signs, sc.cons, sc.neg, sc.pos);
    }
  }
}

/// Traces the last segment of a classification path: from `start` along axis
/// k onto the piece's interior point x on t's plane. Adds crossings to w and
/// collects in `delta` the transition at x of every polygon containing x
/// (t and coplanar overlapping polygons), signed relative to t's orientation.
/// `side` is the side of t's plane S the path arrives from. (t may be unbuilt:
/// the proof classifies in the root soup.)
bool trace_onto(const Soup& soup, const SoupPolygon& t, const Plane& S, const Dyadic& start, int k, const AxisPoint& x,
                Wnv& w, Wnv& delta, int& side, std::uint32_t skip, const SoupApprox* flat) {
  AxisSegment seg;
  if (!onto_segment(S, start, k, x, seg, side)) return false;
  delta.assign(w.size(), 0);
  delta[t.operand] += 1;
  // One loop per kind of miss filter (as in trace_axis_segment); scan_soup
  // shares a root soup's (the proof's) among the threads.
  const SoupPolygon* const polys = soup.data();  // not reloaded after each write to w
  const auto run = [&](auto&& clearly_misses) {
    return scan_soup(soup.size(), w, delta, [&](std::size_t i, Wnv& sum, Wnv& sum_delta, Polygon& built) {
      const SoupPolygon& p = polys[i];
      if (p.id == t.id || p.operand == skip || box_disjoint(p, seg.lo, seg.hi)) return true;
      // A clear miss of the segment's line misses x too (x is on the line), so
      // it decides both cases of meet_onto before its exact coplanarity test.
      if (clearly_misses(i, p)) return true;
      return meet_onto(seg, built_polygon(p, built), p.operand, S, x, sum, sum_delta);
    });
  };
  if (flat)
    return run([&](std::size_t i, const SoupPolygon&) { return line_clearly_misses(seg.line, seg.uv, *flat, i); });
  return run([&](std::size_t, const SoupPolygon& p) { return line_clearly_misses(seg.line, seg.uv, p); });
}

/// Traces from the leaf's reference point to the piece through the dyadic
/// target (u, v) on the piece's dominant axis k, whose line meets the piece
/// strictly inside at x (interior_point). False if the path meets something
/// degenerately.
bool classify_through(const Subproblem& pb, const SoupPolygon& t, const Plane& S, const Dyadic& target, int k,
                      const AxisPoint& x, bool i_first, bool solid, Wnv& w, Wnv& delta, Wnv& w_front, Wnv& w_back,
                      const SoupApprox* flat) {
  const int i = (k + 1) % 3, j = (k + 2) % 3;
  const std::array<int, 3> order = i_first ? std::array<int, 3>{i, j, k} : std::array<int, 3>{j, i, k};
  w = pb.ref_w;
  int side = 0;
  // A solid operand's own polygons never cross t and its winding number is
  // 0 in front of t and 1 behind: they need not be traced at all.
  const std::uint32_t skip = solid ? t.operand : kNoSkip;
  if (!trace_path(pb.soup, pb.ref, target, order, w, skip, flat)) return false;
  if (!trace_onto(pb.soup, t, S, target, k, x, w, delta, side, skip, flat)) return false;
  w_front = w;
  w_back = w;
  for (std::size_t o = 0; o < w.size(); ++o) {
    if (side > 0) {
      w_back[o] += delta[o];
    } else {
      w_front[o] -= delta[o];
    }
  }
  if (solid) {
    w_front[t.operand] = 0;
    w_back[t.operand] = 1;
  }
  return true;
}

/// Classifies one enabled piece of t through the targets of
/// for_each_interior_target (pieces.hpp), paths from the leaf's reference
/// point in the variant's axis order.
bool classify_piece(const Subproblem& pb, const SoupPolygon& t, const Polygon& f, bool solid, std::uint64_t seed,
                    Wnv& w_front, Wnv& w_back, LeafScratch& scratch) {
  const Plane& S = f.support;  // t's plane (t may be unbuilt: the proof's root soup)
  const int k = dominant_axis(S);
  const SoupApprox* flat = scratch.approx;
  return for_each_interior_target(f, pb.ref, seed, [&](const Dyadic& target, const AxisPoint& x, int variant) {
    return classify_through(pb, t, S, target, k, x, variant == 0, solid, scratch.w, scratch.delta, w_front, w_back,
                            flat);
  });
}

}  // namespace

bool classify_polygon(const Subproblem& pb, const SoupPolygon& t, Wnv& w_front, Wnv& w_back) {
  LeafScratch scratch;
  Polygon built;
  return classify_piece(pb, t, built_polygon(t, built), false, t.id, w_front, w_back, scratch);
}

namespace {

/// Whether the built-in operation could be constant on one side of t for
/// some values of the operands that are neither free nor known: `known_in`
/// operands are known inside (t's solid operand behind t), `known` are known
/// at all, `first_known` is operand 0's known state (-2: not known).
/// Every built-in operation is monotone in the count, so the extremes decide.
bool could_be_constant(const SolveContext& ctx, std::size_t free, bool first_free, std::size_t known,
                       std::size_t known_in, int first_known) {
  // An expression need not be monotone in the count: a trace tells (side_value).
  if (ctx.expression) return true;
  if (!ctx.op) return false;
  const std::size_t unknown = ctx.operands - free - known;
  if (first_free || first_known >= 0) {
    const int first = first_free ? -1 : first_known;
    return ctx.over_free(known_in, free, first) >= 0 || ctx.over_free(known_in + unknown, free, first) >= 0;
  }
  // Operand 0 is one of the unknown ones.
  return ctx.over_free(known_in, free, 0) >= 0 || ctx.over_free(known_in + unknown - 1, free, 0) >= 0 ||
         ctx.over_free(known_in + 1, free, 1) >= 0 || ctx.over_free(known_in + unknown, free, 1) >= 0;
}

/// The operation's value on one side of t given the winding numbers traced at
/// one point, when it is the same everywhere along that side (-1 otherwise).
int side_value(const SolveContext& ctx, const Wnv& w, const std::vector<std::uint32_t>& free, std::uint32_t stamp,
               std::size_t n_free) {
  if (ctx.expression) {
    std::array<signed char, 64> small;
    std::vector<signed char> large;
    signed char* state = small.data();
    if (w.size() > small.size()) state = (large.resize(w.size()), large.data());
    for (std::size_t o = 0; o < w.size(); ++o) state[o] = free[o] == stamp ? -1 : (w[o] != 0 ? 1 : 0);
    return ctx.expression->value_over(std::span<const signed char>(state, w.size()));
  }
  std::size_t inside = 0;
  for (std::size_t o = 0; o < w.size(); ++o) inside += w[o] != 0 && free[o] != stamp;
  const int first = free[0] == stamp ? -1 : (w[0] != 0 ? 1 : 0);
  return ctx.over_free(inside, n_free, first);
}

}  // namespace

namespace {

/// The direction class of a polygon's plane: the normal divided by the gcd of
/// its components, pointing into the positive half of its first non-zero
/// axis. Parallel planes (either orientation), and only they, share it.
std::array<std::int64_t, 3> direction_key(const Plane& p) {
  std::array<std::int64_t, 3> n{static_cast<std::int64_t>(p.a.raw()), static_cast<std::int64_t>(p.b.raw()),
                                static_cast<std::int64_t>(p.c.raw())};
  std::int64_t g = 0;
  for (const std::int64_t v : n) g = std::gcd(g, v < 0 ? -v : v);
  if (g == 0) return n;
  const std::int64_t first = n[0] != 0 ? n[0] : (n[1] != 0 ? n[1] : n[2]);
  if (first < 0) g = -g;
  for (std::int64_t& v : n) v /= g;
  return n;
}

/// What every polygon of a leaf reads, built once per leaf: the classes of
/// parallel polygons (so that the coplanar overlaps of a stack are found
/// among its parallel polygons, not the whole leaf) and, in pile leaves, the
/// filters' approximations and frame boxes.
struct LeafIndex {
  std::vector<std::uint32_t> order;                             ///< soup indices grouped by direction class
  std::vector<std::uint32_t> class_begin, class_end, position;  ///< per polygon: its class in `order`, its place there
  SoupApprox approx;
  FrameBoxes frame;
  bool pile = false;
};

/// Leaves over this size get the pile filters (approximations, frame boxes,
/// the frame grid); "pile leaf" in this file means such a leaf. The filters
/// are named for piles (thousands of polygons), but a leaf of the usual
/// size is already worth them: gather is quadratic in the leaf, the set-up
/// linear. At 16, leaves of the usual size get the filters, as do the
/// leaves of a few hundred polygons that fans of coplanar slivers leave and
/// no split pays for; the cost changes little for thresholds near it. The
/// filters only narrow the candidates, so the output is the same.
constexpr std::size_t kPileLeaf = 16;

LeafIndex index_leaf(const Soup& soup) {
  const std::size_t size = soup.size();
  LeafIndex index;
  std::vector<std::pair<std::array<std::int64_t, 3>, std::uint32_t>> keyed(size);
  for (std::size_t i = 0; i < size; ++i)
    keyed[i] = {direction_key(soup[i].poly->support), static_cast<std::uint32_t>(i)};
  std::sort(keyed.begin(), keyed.end());
  index.order.resize(size);
  index.class_begin.resize(size);
  index.class_end.resize(size);
  index.position.resize(size);
  for (std::size_t i = 0; i < size;) {
    std::size_t j = i;
    while (j < size && keyed[j].first == keyed[i].first) ++j;
    for (std::size_t k = i; k < j; ++k) {
      index.order[k] = keyed[k].second;
      index.class_begin[keyed[k].second] = static_cast<std::uint32_t>(i);
      index.class_end[keyed[k].second] = static_cast<std::uint32_t>(j);
      index.position[keyed[k].second] = static_cast<std::uint32_t>(k - i);
    }
    i = j;
  }
  if (size > kPileLeaf) {
    index.pile = true;
    approximate(soup, index.approx);
    std::vector<std::uint32_t> operand(size);
    for (std::size_t i = 0; i < size; ++i) operand[i] = soup[i].operand;
    index.frame = FrameBoxes(index.approx, operand);
  }
  return index;
}

/// Cuts and classifies the leaf's polygons [begin, end) and emits their
/// enabled pieces in soup order.
void solve_polygons(const Subproblem& pb, const SolveContext& ctx, const LeafIndex& index, std::size_t begin,
                    std::size_t end, std::vector<OutputPolygon>& out) {
  const std::vector<std::uint32_t>&order = index.order, &class_begin = index.class_begin, &class_end = index.class_end,
        &position = index.position;
  Wnv w_front, w_back;
  LeafScratch scratch;
  if (index.pile) {
    scratch.approx = &index.approx;
    scratch.frame = index.frame.empty() ? nullptr : &index.frame;
  }
  std::vector<Piece> pieces;
  const auto classify_or_throw = [&](const SoupPolygon& t, const Polygon& f, std::uint64_t seed) {
    if (!classify_piece(pb, t, f, ctx.solid[t.operand] != 0, seed, w_front, w_back, scratch))
      throw Error(
          "ember: could not classify a polygon piece (no non-degenerate trace path found); "
          "this input is too degenerate for the current implementation");
  };
  // Polygons are solved in edge_neighbour_order, so that more of them take
  // their winding numbers across input edges (far fewer traces than in soup
  // order, where consecutive polygons are rarely neighbours), and their pieces are emitted in soup
  // order: `produced` holds them by polygon, from produced_from[ti - begin] on.
  std::vector<OutputPolygon> produced;
  std::vector<std::size_t> produced_from(end - begin);
  // `whole`: f is all of t (t's subdivision piece), uncut and untrimmed.
  const auto emit = [&](const SoupPolygon& t, const Polygon& f, const Crossing& crossing, bool whole) {
    if (!crossing.emitted) return;
    if (whole) {
      // f is t's whole subdivision piece: emitted without its vertices
      // (unbuilt or by path, solve.hpp), like the early-outs' pieces.
      produced.push_back(whole_piece_output(t, crossing));
      return;
    }
    // The mesh stage needs a cut piece's vertices, not its edge planes.
    OutputPolygon piece;
    piece.vertices = f.vertices;
    piece.corners = t.corners;
    piece.id = t.id;
    piece.operand = t.operand;
    piece.flip = crossing.flip;
    piece.layer_lo = crossing.lo;
    piece.layer_hi = crossing.hi;
    piece.splits = t.splits;
    produced.push_back(std::move(piece));
  };
  // Each polygon records its pieces' edges on its three input edges; a
  // leaf's pieces are about as many as its polygons. Piles (thousands of
  // polygons) grow the table as needed.
  constexpr std::size_t kMaxExpectedEdges = 4096;
  EdgeWindings known(ctx.closed, pb.box, std::min(3 * (end - begin), kMaxExpectedEdges));
  std::vector<char> need_front(ctx.operands), need_back(ctx.operands), all(ctx.operands, 1);
  const std::vector<std::uint32_t> visit = edge_neighbour_order(pb.soup, begin, end);
  for (const std::uint32_t ti : visit) {
    produced_from[ti - begin] = produced.size();
    const SoupPolygon& t = pb.soup[ti];
    const bool uncovered =
        disable_covered(pb.soup, t, ctx,
                        std::span<const std::uint32_t>(order.data() + class_begin[ti], class_end[ti] - class_begin[ti]),
                        position[ti], scratch, pieces);
    if (pieces.empty()) continue;
    gather(pb.soup, t, ctx, class_begin, scratch);
    const bool face = on_box_face(t, pb.box);
    // Neighbours across input edges hand over their winding numbers
    // (edge_windings.hpp), except in a box face, where one side of t is
    // outside the box.
    const bool share = ctx.share_edge_windings && !face;
    if (share) {
      known.begin_polygon(pb.soup, t, scratch.related);
      for (std::size_t o = 0; o < ctx.operands; ++o) {
        need_front[o] = scratch.free_front[o] != scratch.stamp;
        need_back[o] = scratch.free_back[o] != scratch.stamp;
      }
    }
    // Piece-level early termination (Section 4.5.2 applied to one polygon):
    // if the operands whose winding numbers can change along either side of t
    // cannot change the result there, one trace classifies the whole piece and
    // no further cut is needed. Only when t has a known side (inside the box).
    const bool solid = ctx.solid[t.operand] != 0;
    const bool maybe_constant = !face &&
                                could_be_constant(ctx, scratch.n_front, scratch.free_front[0] == scratch.stamp,
                                                  solid ? 1 : 0, 0, solid && t.operand == 0 ? 0 : -2) &&
                                could_be_constant(ctx, scratch.n_back, scratch.free_back[0] == scratch.stamp,
                                                  solid ? 1 : 0, solid ? 1 : 0, solid && t.operand == 0 ? 1 : -2);
    const std::size_t n_pieces = pieces.size();
    for (std::size_t n = 0; n < n_pieces; ++n) {
      const std::uint64_t seed = (static_cast<std::uint64_t>(t.id) << 20) ^ (n << 10);
      // w_front / w_back hold for every operand over the whole piece: a trace
      // to a point of it, or a neighbour's values that hold for all operands.
      bool exact = false;
      if (maybe_constant) {
        // Only the operands that are not free on a side matter here.
        if (!(share && known.find(pieces[n].poly, need_front, need_back, w_front, w_back, exact))) {
          classify_or_throw(t, pieces[n].poly, seed);
          exact = true;
        }
        const int vf = side_value(ctx, w_front, scratch.free_front, scratch.stamp, scratch.n_front);
        const int vb = side_value(ctx, w_back, scratch.free_back, scratch.stamp, scratch.n_back);
        if (vf >= 0 && vb >= 0) {
          emit(t, pieces[n].poly, Crossing{vf != vb, vf != 0}, uncovered);
          if (share) known.record(pieces[n].poly, w_front, w_back, need_front, need_back);
          continue;
        }
      }
      std::vector<Piece>& sub = scratch.sub;
      sub.resize(1);
      sub[0].poly = pieces[n].poly;
      refine(pb.soup, t, ctx, face, scratch, sub);
      for (std::size_t m = 0; m < sub.size(); ++m) {
        // Uncut: the values found for the early termination still hold.
        bool full = exact && sub.size() == 1;
        if (!full && share) full = known.find(sub[m].poly, all, all, w_front, w_back, full) && full;
        if (!full) classify_or_throw(t, sub[m].poly, seed + m);
        emit(t, sub[m].poly, ctx.crossing(w_front, w_back), uncovered && sub.size() == 1);
        if (share) known.record(sub[m].poly, w_front, w_back, all, all);
      }
    }
  }
  // In soup order: polygon ti's pieces run up to the next polygon's start in
  // the visiting order.
  std::vector<std::size_t> produced_to(end - begin);
  for (std::size_t k = 0; k < visit.size(); ++k)
    produced_to[visit[k] - begin] = k + 1 < visit.size() ? produced_from[visit[k + 1] - begin] : produced.size();
  out.reserve(out.size() + produced.size());
  for (std::size_t i = 0; i < end - begin; ++i)
    std::move(produced.begin() + static_cast<std::ptrdiff_t>(produced_from[i]),
              produced.begin() + static_cast<std::ptrdiff_t>(produced_to[i]), std::back_inserter(out));
}

}  // namespace

void solve_leaf(const Subproblem& pb, const SolveContext& ctx, std::vector<OutputPolygon>& out) {
  const LeafIndex index = index_leaf(pb.soup);
  const std::size_t size = pb.soup.size();
  // A pile leaf (thousands of polygons that no split separates) is shared by
  // the threads in fixed blocks of
  // polygons, so the pieces and their order are the same at any thread count.
  // Each block hands winding numbers across input edges only among its own
  // polygons (edge_windings.hpp): the values are exact either way, but each
  // block boundary costs traces: 512 polygons a block keeps those traces
  // few while still giving the threads several blocks of a pile leaf.
  constexpr std::size_t kBlock = 512;
  if (size <= kBlock) {  // one block: no tasks, no copy
    solve_polygons(pb, ctx, index, 0, size, out);
    return;
  }
  std::vector<std::vector<OutputPolygon>> blocks((size + kBlock - 1) / kBlock);
  // Isolated: a thread waiting for the leaf's blocks takes no unrelated
  // subtree of the subdivision (seconds on a pile) that would hold the leaf.
  tbb::this_task_arena::isolate([&] {
    tbb::parallel_for(std::size_t{0}, blocks.size(), [&](std::size_t b) {
      solve_polygons(pb, ctx, index, b * kBlock, std::min(size, (b + 1) * kBlock), blocks[b]);
    });
  });
  std::size_t total = out.size();
  for (const auto& b : blocks) total += b.size();
  out.reserve(total);
  for (auto& b : blocks) std::move(b.begin(), b.end(), std::back_inserter(out));
}

}  // namespace ember::core
