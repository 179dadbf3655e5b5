// The solid path (solid_route.hpp): broad phase on per-operand triangle
// trees, polygon-local BSPs of the touched triangles, classification by
// traces from outside, untouched triangles by components.
#include "core/route/solid/solid_route.hpp"
#include "core/model/components.hpp"
#include "core/search/triangle_contact.hpp"

#include <tbb/blocked_range.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_invoke.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <bit>
#include <cassert>
#include <optional>

#include "core/search/frame_sample.hpp"
#include "core/search/leaf_frame_extents.hpp"
#include "core/search/operand_trees.hpp"
#include "core/support/parallel_select.hpp"
#include "core/route/shared/pieces.hpp"
#include "core/route/solid/solid_cuts.hpp"
#include "core/route/solid/solid_handover.hpp"
#include "core/route/solid/solid_trace.hpp"

namespace ember::core {

namespace {

/// A box's largest side (grid units): which of two triangles is the larger.
std::int32_t extent(const Box32& b) { return std::max({b.hi[0] - b.lo[0], b.hi[1] - b.lo[1], b.hi[2] - b.lo[2]}); }

using PairSink = tbb::enumerable_thread_specific<std::vector<std::pair<std::uint32_t, std::uint32_t>>>;

/// The partner search's work so far against its budget (find_partners):
/// the slot pairs of the leaf pairs it visits (kLeaf^2 each: one addition
/// per leaf pair, where counting per triangle, as the contact search does,
/// would add work to the innermost loop), added up per task in batches of
/// kFlush.
struct Work {
  static constexpr std::size_t kFlush = std::size_t{1} << 14;
  std::size_t budget;
  std::atomic<std::size_t> examined{0};
  std::atomic<bool> over{false};
  /// Adds a task's count; true once the budget is passed.
  bool flush(std::size_t& local) {
    if (examined.fetch_add(local, std::memory_order_relaxed) + local > budget) over.store(true);
    local = 0;
    return over.load(std::memory_order_relaxed);
  }
};

/// popcount(m) > 2 without std::popcount, which compiles to a libgcc call
/// on the baseline x86-64 target, in a loop that runs once per triangle of
/// every leaf pair.
constexpr bool more_than_two_bits(unsigned m) {
  m &= m - 1;  // the lowest set bit cleared, twice
  m &= m - 1;
  return m != 0;
}
static_assert(!more_than_two_bits(0b101) && more_than_two_bits(0b10101) && !more_than_two_bits(0) &&
              more_than_two_bits(~0u));

/// Operands with fewer triangles get no common frame (partner_frame).
constexpr std::size_t kPartnerFrameMin = 256;

/// One operand's side of the partner search: its tree, its leaves'
/// diagonal extents, the id of its item 0, and, where the pair of operands
/// has one (partner_frame), its extents in their common frame.
struct Side {
  const TriangleTree& tree;
  const LeafDiagonals& diagonals;
  std::uint32_t base;
  const LeafFrameExtents* frame = nullptr;
};

/// The meeting pairs of leaf x of X and leaf y of Y: each of x's triangles
/// whose box meets y's against y's triangles whose boxes and diagonal
/// extents meet its own, by x's plane first (apart_triangles_meet). Reported
/// as (x's id, y's id), or swapped.
/// Inlined: it runs once per leaf pair, most of which test few pairs, so a
/// call's overhead would weigh on every one of them.
template <bool swap, bool Wide, bool Framed>
[[gnu::always_inline]] inline void leaf_meeting_pairs(const GridTriangles& grid, const Side& xs, std::size_t x,
                                                      const Side& ys, std::size_t y, PairSink& sink) {
  const TriangleTree &X = xs.tree, &Y = ys.tree;
  const std::uint32_t x_base = xs.base, y_base = ys.base;
  const std::size_t xb = X.leaf_slots(x).first, yb = Y.leaf_slots(y).first;
  const Box32 y_box = Y.node(y);
  // x's triangles whose boxes meet y's node box, eight at a time.
  for (unsigned near = X.overlap_mask_in<Wide>(x, y_box); near != 0; near &= near - 1) {
    const std::size_t i = xb + static_cast<std::size_t>(std::countr_zero(near));
    unsigned m = Y.overlap_mask_in<Wide>(y, X.box(i));
    // Framed: first the extents in the operands' common frame (an operand of
    // slivers beside or inside the other).
    if constexpr (Framed)
      if (m != 0) m &= ~ys.frame->apart_mask_in<Wide>(y, xs.frame->extent(i));
    // Boxes that meet, diagonal extents that do not (a good share of the
    // pairs the boxes leave, even on ordinary meshes), eight at a time.
    if (m != 0) m &= ~ys.diagonals.apart_mask_in<Wide>(y, xs.diagonals.extent(i));
    if (m == 0) continue;
    const std::uint32_t ix = x_base + X.item(i);
    const std::array<IntPoint, 3>& tx = grid.corners[ix];
    const std::array<std::int64_t, 3>& nx = grid.normals[ix];
    // All of y beside x's plane: none of its triangles meets x (where the
    // operands lie side by side, most of the pairs the boxes leave,
    // dismissed eight at a time). Not for one or two pairs, whose own tests
    // cost about as much as this one.
    if (more_than_two_bits(m) && box_clearly_beside(y_box, tx[0], nx)) continue;
    // Most of the rest lie beside x's plane too: their sides in double first.
    const PlaneSideFilter x_plane(tx[0], nx);
    for (; m != 0; m &= m - 1) {
      const std::uint32_t iy = y_base + Y.item(yb + static_cast<std::size_t>(std::countr_zero(m)));
      const std::array<IntPoint, 3>& ty = grid.corners[iy];
      const CornerSigns sides = x_plane.signs(ty);
      if (sides.strictly_one_side()) continue;
      if (apart_triangles_meet(tx, nx, ty, grid.normals[iy], sides))
        sink.local().emplace_back(swap ? iy : ix, swap ? ix : iy);
    }
  }
}

/// The meeting pairs of leaves a of A and b of B (leaf_meeting_pairs).
/// The first test of a pair (the other's corners against one plane)
/// rejects most pairs, but only with the larger triangle's plane: a small
/// triangle beside a large one's plane has the large one crossing its own
/// (between a fine mesh and a coarse one, most pairs pass the test by the
/// small triangle's plane and fail the one by the large one's). Which is
/// larger is judged once per
/// leaf pair, by the leaves' boxes. The answer is exact either way, and the
/// pairs are sorted after. Wide: the 8-lane leaf tests (wide_lanes.hpp).
template <bool Wide, bool Framed>
[[gnu::always_inline]] inline void leaf_pair(const GridTriangles& grid, const Side& as, std::size_t a, const Side& bs,
                                             std::size_t b, PairSink& sink) {
  if (extent(bs.tree.node(b)) > 2 * extent(as.tree.node(a))) {
    leaf_meeting_pairs<true, Wide, Framed>(grid, bs, b, as, a, sink);
  } else {
    leaf_meeting_pairs<false, Wide, Framed>(grid, as, a, bs, b, sink);
  }
}

/// A pair of subtrees still to visit: node a of A at depth da, node b of B
/// at depth db, their boxes overlapping.
struct NodePair {
  std::size_t a, b;
  int da, db;
};

/// Nodes a of A and b of B may hold a meeting pair: their boxes overlap,
/// and where the operands have a common frame, their frame hulls too.
template <bool Framed>
bool nodes_may_meet(const Side& as, std::size_t a, const Side& bs, std::size_t b) {
  if (!overlap(as.tree.node(a), bs.tree.node(b))) return false;
  if constexpr (Framed) return !as.frame->nodes_apart(a, *bs.frame, b);
  return true;
}

/// The same, with the frame's test where the operands have one.
bool nodes_may_meet(const Side& as, std::size_t a, const Side& bs, std::size_t b) {
  return as.frame ? nodes_may_meet<true>(as, a, bs, b) : nodes_may_meet<false>(as, a, bs, b);
}

/// Which side of a node pair to descend: the one with more levels below
/// (node sizes stay alike); none when both are leaves.
bool descend_a(const TriangleTree& A, const TriangleTree& B, const NodePair& v) {
  return v.da != A.depth() && (v.db == B.depth() || A.depth() - v.da >= B.depth() - v.db);
}

/// Every meeting pair under node pair `root`, depth first with a stack of
/// its own: as a recursion each node pair would pay for calls and spills,
/// and a search visits several node pairs per leaf pair it reaches.
/// A descent adds at most one pending pair per level of either tree, and
/// a tree holds fewer than 2^32 triangles, 8 per leaf (< 30 levels).
/// Stops once the search is over its budget or `stop` is set (checked at
/// each flush of the work count).
template <bool Wide, bool Framed>
[[gnu::always_inline]] inline void subtree_pairs(const GridTriangles& grid, const Side& as, const Side& bs,
                                                 const NodePair& root, PairSink& sink, Work& work,
                                                 const std::atomic<bool>& stop) {
  const TriangleTree &A = as.tree, &B = bs.tree;
  assert(A.depth() + B.depth() < 126);
  std::array<NodePair, 128> stack;
  std::size_t top = 0;
  stack[top++] = root;
  std::size_t examined = 0;
  while (top > 0) {
    const NodePair v = stack[--top];
    if (v.da == A.depth() && v.db == B.depth()) {
      // Both leaves hold triangles: an empty leaf's box is empty and meets no
      // box, so no pair with one passed nodes_may_meet.
      assert(A.leaf_slots(v.a).first < A.size() && B.leaf_slots(v.b).first < B.size());
      leaf_pair<Wide, Framed>(grid, as, v.a, bs, v.b, sink);
      examined += TriangleTree::kLeaf * TriangleTree::kLeaf;
      if (examined >= Work::kFlush && (work.flush(examined) || stop.load(std::memory_order_relaxed))) return;
      continue;
    }
    // Child 1 pushed first: child 0 is visited first, as the recursion did.
    if (descend_a(A, B, v)) {
      for (std::size_t c = 2 * v.a + 2; c > 2 * v.a; --c)
        if (nodes_may_meet<Framed>(as, c, bs, v.b)) stack[top++] = {c, v.b, v.da + 1, v.db};
    } else {
      for (std::size_t c = 2 * v.b + 2; c > 2 * v.b; --c)
        if (nodes_may_meet<Framed>(as, v.a, bs, c)) stack[top++] = {v.a, c, v.da, v.db + 1};
    }
  }
  work.flush(examined);
}

#if EMBER_WIDE_LANES
template <bool Framed>
EMBER_TARGET_AVX2 void subtree_pairs_wide(const GridTriangles& grid, const Side& as, const Side& bs,
                                          const NodePair& root, PairSink& sink, Work& work,
                                          const std::atomic<bool>& stop) {
  subtree_pairs<true, Framed>(grid, as, bs, root, sink, work, stop);
}
#endif

/// Collects every pair of A x B that meets (boxes first, then exactly:
/// triangles_meet) under node pair v, whose boxes overlap (the caller tests
/// them: most child pairs do not overlap, and the test costs less than a
/// call). Large subtrees as parallel tasks, the rest by subtree_pairs. Stops
/// early once `stop` is set (the run is abandoned: the pairs are not used)
/// or the work passes its budget. wide: cpu_has_avx2().
void meeting_pairs(const GridTriangles& grid, const Side& as, const Side& bs, const NodePair& v, PairSink& sink,
                   Work& work, const std::atomic<bool>& stop, bool wide) {
  const TriangleTree &A = as.tree, &B = bs.tree;
  constexpr int kParallelLevels = 6;
  const bool split_a = descend_a(A, B, v);
  if ((split_a ? A.depth() - v.da : B.depth() - v.db) < kParallelLevels) {
    // Each combination compiled apart: the frame's tests cost nothing where
    // the operands have none.
    const bool framed = as.frame != nullptr;
#if EMBER_WIDE_LANES
    if (wide)
      return framed ? subtree_pairs_wide<true>(grid, as, bs, v, sink, work, stop)
                    : subtree_pairs_wide<false>(grid, as, bs, v, sink, work, stop);
#endif
    return framed ? subtree_pairs<false, true>(grid, as, bs, v, sink, work, stop)
                  : subtree_pairs<false, false>(grid, as, bs, v, sink, work, stop);
  }
  // Here, above the small subtrees, once per task (and in them once per
  // flush of the work count). (A proof that finds a self-intersection sets
  // `stop`; otherwise a speculative run over a pile of slivers would search
  // its nearly all-pairs to the end.)
  if (stop.load(std::memory_order_relaxed) || work.over.load(std::memory_order_relaxed)) return;
  const auto child = [&](std::size_t c) {
    const NodePair w =
        split_a ? NodePair{2 * v.a + 1 + c, v.b, v.da + 1, v.db} : NodePair{v.a, 2 * v.b + 1 + c, v.da, v.db + 1};
    if (nodes_may_meet(as, w.a, bs, w.b)) meeting_pairs(grid, as, bs, w, sink, work, stop, wide);
  };
  tbb::parallel_invoke([&] { child(0); }, [&] { child(1); });
}

}  // namespace

std::optional<FrameAxes> partner_frame(std::span<const std::array<IntPoint, 3>> x,
                                       std::span<const std::array<IntPoint, 3>> y, const TriangleTree& y_tree) {
  // Small operands: their search costs less than the sample, which a pile
  // of many small operands would otherwise pay for each overlapping pair.
  if (std::min(x.size(), y.size()) < kPartnerFrameMin) return std::nullopt;
  const auto x_corners = [&](std::size_t i) -> const std::array<IntPoint, 3>& { return x[i]; };
  const auto y_corners = [&](std::size_t j) -> const std::array<IntPoint, 3>& { return y[j]; };
  std::array<FrameAxes, 2> frames;
  if (!principal_frame(frame_points(x.size(), x_corners), frames[0]) ||
      !principal_frame(frame_points(y.size(), y_corners), frames[1]))
    return std::nullopt;
  std::size_t sampled = 0;
  const std::array<std::size_t, 2> dismissed =
      frame_dismissals<2>(x.size(), x_corners, y_tree, y_corners, frames, false, sampled);
  const std::size_t best = dismissed[1] > dismissed[0] ? 1 : 0;
  if (static_cast<double>(dismissed[best]) < kFramePairsPerTriangle * static_cast<double>(sampled)) return std::nullopt;
  return frames[best];
}

Partners find_partners(const GridTriangles& grid, const OperandTrees& trees, std::size_t n,
                       const std::atomic<bool>& stop, std::size_t budget) {
  PairSink sink;
  Work work{budget};
  const bool wide = cpu_has_avx2();
  const std::size_t operands = trees.tree.size();
  assert(trees.diagonals.size() == operands);  // boolean frees them only after this search
  assert(grid.normals.size() == grid.corners.size());
  for (std::size_t a = 0; a < operands; ++a)
    for (std::size_t b = a + 1; b < operands; ++b) {
      Side as{trees.tree[a], trees.diagonals[a], trees.begin[a]}, bs{trees.tree[b], trees.diagonals[b], trees.begin[b]};
      if (as.tree.empty() || bs.tree.empty() || !overlap(as.tree.node(0), bs.tree.node(0))) continue;
      const auto own = [&](std::size_t o) {
        return std::span(grid.corners).subspan(trees.begin[o], trees.begin[o + 1] - trees.begin[o]);
      };
      std::optional<LeafFrameExtents> a_frame, b_frame;
      if (const std::optional<FrameAxes> frame = partner_frame(own(a), own(b), bs.tree)) {
        a_frame.emplace(as.tree, own(a), *frame);
        b_frame.emplace(bs.tree, own(b), *frame);
        as.frame = &*a_frame;
        bs.frame = &*b_frame;
      }
      if (nodes_may_meet(as, 0, bs, 0)) meeting_pairs(grid, as, bs, NodePair{0, 0, 0, 0}, sink, work, stop, wide);
    }
  Partners p;
  if (work.over.load()) {
    p.gave_up = true;
    return p;
  }
  // Counting sort by triangle, then each list ascending (lists are short,
  // and the result does not depend on the order pairs were found in).
  p.begin.assign(n + 1, 0);
  for (const auto& local : sink)
    for (const auto& [x, y] : local) {
      ++p.begin[x + 1];
      ++p.begin[y + 1];
    }
  for (std::size_t i = 0; i < n; ++i) p.begin[i + 1] += p.begin[i];
  p.ids.resize(p.begin[n]);
  std::vector<std::uint32_t> fill(p.begin.begin(), p.begin.end() - 1);
  for (const auto& local : sink)
    for (const auto& [x, y] : local) {
      p.ids[fill[x]++] = y;
      p.ids[fill[y]++] = x;
    }
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, 1024), [&](const tbb::blocked_range<std::size_t>& r) {
    for (std::size_t i = r.begin(); i != r.end(); ++i)
      std::sort(p.ids.begin() + p.begin[i], p.ids.begin() + p.begin[i + 1]);
  });
  return p;
}

namespace {

/// The output form of grid triangle `id` (of `operand`) whole (unbuilt), or
/// of one of its pieces.
OutputPolygon output_of(const GridTriangles& grid, std::uint32_t id, std::uint32_t operand, const Polygon* piece,
                        const Crossing& crossing) {
  OutputPolygon out;
  if (piece) out.vertices.assign(piece->vertices.begin(), piece->vertices.end());
  out.corners = &grid.corners[id];
  out.id = id;
  out.operand = operand;
  out.flip = crossing.flip;
  out.layer_lo = crossing.lo;
  out.layer_hi = crossing.hi;
  out.whole_piece = !piece;
  return out;
}

/// The untouched triangles joined across manifold edges: roots (each
/// component's smallest id, ascending) and, per untouched triangle, its
/// component's index in `roots`.
struct Components {
  FillVector<std::uint32_t> roots;
  FillVector<std::uint32_t> index;
};

/// Per triangle, whether another operand's triangle meets it (in parallel:
/// a serial pass over every triangle is a stretch of one thread's work).
FillVector<char> touched_flags(const Partners& partners, std::size_t n) {
  FillVector<char> touched(n);  // every entry written here
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, 16384), [&](const tbb::blocked_range<std::size_t>& r) {
    for (std::size_t i = r.begin(); i != r.end(); ++i) touched[i] = partners.touched(static_cast<std::uint32_t>(i));
  });
  return touched;
}

Components untouched_components(const GridTriangles& grid, std::span<const char> touched) {
  const std::size_t n = touched.size();
  FillVector<char> untouched(n);  // every entry written here
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, 16384), [&](const tbb::blocked_range<std::size_t>& r) {
    for (std::size_t i = r.begin(); i != r.end(); ++i) untouched[i] = !touched[i];
  });
  Components c;
  c.index = neighbour_components(grid, untouched);  // each untouched triangle's root: its component's smallest id
  c.roots = parallel_indices_where(n, [&](std::size_t i) { return untouched[i] && c.index[i] == i; });
  // Each member takes its root's rank among the roots, in two parallel
  // passes (a serial pass over every triangle did it in one).
  FillVector<std::uint32_t> rank(n);  // written at the roots only, and read only there
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, c.roots.size(), 16384),
                    [&](const tbb::blocked_range<std::size_t>& r) {
                      for (std::size_t k = r.begin(); k != r.end(); ++k)
                        rank[c.roots[k]] = static_cast<std::uint32_t>(k);
                    });
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, 16384), [&](const tbb::blocked_range<std::size_t>& r) {
    for (std::size_t i = r.begin(); i != r.end(); ++i)
      if (untouched[i]) c.index[i] = rank[c.index[i]];
  });
  return c;
}

/// An untouched triangle across one of t's input edges along which piece f
/// has an edge (of positive length: f is strictly convex), or kNoNeighbor.
/// f's edges on t's edges keep t's edge planes (clip copies them).
std::uint32_t untouched_neighbour_along(const Polygon& f, const Polygon& t,
                                        const std::array<std::uint32_t, 3>& neighbours, std::span<const char> touched) {
  for (int k = 0; k < 3; ++k) {
    const std::uint32_t u = neighbours[k];
    if (u == kNoNeighbor || touched[u]) continue;
    for (const Plane& e : f.edges)
      if (e == t.edges[k]) return u;
  }
  return kNoNeighbor;
}

/// Steps 2-4 of the solid path over the partners of step 1.
class SolidSolver {
 public:
  SolidSolver(const GridTriangles& grid, const Box& box, const SolveContext& ctx, const OperandTrees& trees,
              const Partners& partners, const std::atomic<bool>& stop)
      : grid_(grid),
        ctx_(ctx),
        trees_(trees),
        partners_(partners),
        stop_(stop),
        operands_(ctx.operands),
        tracer_{grid.corners, trees, box, ctx.operands},
        touched_(touched_flags(partners, grid.corners.size())) {
    comps_ = untouched_components(grid, touched_);
  }

  /// Step 2: one trace per component of untouched triangles. False if a
  /// trace found no non-degenerate path (or the run was abandoned).
  bool classify_components() {
    comp_w_.assign(2 * operands_ * comps_.roots.size(), 0);  // per component: front, then back
    std::atomic<bool> failed{false};
    tbb::parallel_for(
        tbb::blocked_range<std::size_t>(0, comps_.roots.size(), 16), [&](const tbb::blocked_range<std::size_t>& r) {
          TraceScratch sc;
          Polygon t;
          Wnv front, back;
          for (std::size_t k = r.begin(); k != r.end() && !failed.load() && !stop_.load(); ++k) {
            const std::uint32_t id = comps_.roots[k];
            const std::array<IntPoint, 3>& c = grid_.corners[id];
            assign_triangle(c[0], c[1], c[2], t);
            if (!classify_from_outside(tracer_, t, trees_.operand_of(id), std::uint64_t{id} << 20, front, back, sc)) {
              failed = true;
              break;
            }
            std::copy(front.begin(), front.end(), comp_w_.begin() + static_cast<std::ptrdiff_t>(2 * operands_ * k));
            std::copy(back.begin(), back.end(),
                      comp_w_.begin() + static_cast<std::ptrdiff_t>(2 * operands_ * k + operands_));
          }
        });
    return !failed && !stop_.load();
  }

  /// Step 3: touched triangles, in curve order per operand (partners repeat
  /// from one triangle to the next), in fixed chunks: each chunk's output is
  /// ordered, so the result does not depend on the schedule. False if a
  /// trace failed (or the run was abandoned).
  bool solve_touched(std::vector<std::vector<OutputPolygon>>& chunk_out) const {
    std::vector<std::pair<std::uint32_t, std::uint32_t>> chunks;  // (operand, first slot)
    for (std::uint32_t o = 0; o < operands_; ++o)
      for (std::size_t s = 0; s < trees_.tree[o].size(); s += kChunk)
        chunks.emplace_back(o, static_cast<std::uint32_t>(s));
    chunk_out.assign(chunks.size(), {});
    std::atomic<bool> failed{false};
    // The built polygons outlive a range of chunks: a pile's triangles share
    // their partners from one operand's chunk to the next (a pile of many
    // one-chunk operands would otherwise build each shared partner once per
    // chunk). Their content depends only on the id.
    tbb::enumerable_thread_specific<PolygonCache> caches([&] { return PolygonCache(grid_); });
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, chunks.size(), 1),
                      [&](const tbb::blocked_range<std::size_t>& r) {
                        ChunkScratch cs(caches.local(), operands_);
                        for (std::size_t c = r.begin(); c != r.end() && !failed.load() && !stop_.load(); ++c)
                          if (!solve_chunk(chunks[c].first, chunks[c].second, cs, chunk_out[c], failed)) failed = true;
                      });
    return !failed && !stop_.load();
  }

  /// The untouched triangles on the result's surface, by id, each with its
  /// orientation: one trace per component decided them (step 2).
  /// Selected in parallel (a serial push_back of every kept triangle was
  /// most of a large, lightly touched Boolean's solve, and slower at 2
  /// threads than at 1).
  FillVector<KeptTriangle> kept_untouched(const std::vector<Crossing>& crossings) const {
    return parallel_select<KeptTriangle>(
        grid_.corners.size(), [&](std::size_t i) { return !touched_[i] && crossings[comps_.index[i]].emitted; },
        [&](std::size_t i) {
          return KeptTriangle{static_cast<std::uint32_t>(i), crossings[comps_.index[i]].flip};
        });
  }

  /// Per component, how the result crosses its untouched triangles.
  std::vector<Crossing> component_crossings() const {
    std::vector<Crossing> crossings(comps_.roots.size());
    Wnv front, back;
    for (std::size_t k = 0; k < comps_.roots.size(); ++k) {
      component_w(comps_.roots[k], front, back);
      crossings[k] = ctx_.crossing(front, back);
    }
    return crossings;
  }

  /// Step 4: the kept untouched triangles by id, then the chunks in order.
  std::vector<OutputPolygon> output(std::vector<std::vector<OutputPolygon>> chunk_out) const {
    const std::vector<Crossing> crossings = component_crossings();
    const FillVector<KeptTriangle> kept = kept_untouched(crossings);
    std::vector<std::size_t> at(chunk_out.size() + 1, kept.size());
    for (std::size_t c = 0; c < chunk_out.size(); ++c) at[c + 1] = at[c] + chunk_out[c].size();
    std::vector<OutputPolygon> out(at.back());
    // An untouched triangle whose neighbours are all untouched is settled
    // (OutputPolygon::settled): no other operand comes near it or them, and
    // its own operand meets it only in shared vertices and these edges.
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, kept.size(), 4096),
                      [&](const tbb::blocked_range<std::size_t>& r) {
                        for (std::size_t k = r.begin(); k != r.end(); ++k) {
                          const std::uint32_t id = kept[k].id;
                          OutputPolygon& o = out[k];
                          o = output_of(grid_, id, trees_.operand_of(id), nullptr, crossings[comps_.index[id]]);
                          o.settled = std::none_of(grid_.neighbors[id].begin(), grid_.neighbors[id].end(),
                                                   [&](std::uint32_t j) { return j == kNoNeighbor || touched_[j]; });
                        }
                      });
    tbb::parallel_for(std::size_t{0}, chunk_out.size(), [&](std::size_t c) {
      std::move(chunk_out[c].begin(), chunk_out[c].end(), out.begin() + static_cast<std::ptrdiff_t>(at[c]));
    });
    return out;
  }

 private:
  static constexpr std::size_t kChunk = 256;
  /// At least this many pieces of one triangle to trace: traced side by side.
  static constexpr std::size_t kParallelTraces = 64;

  /// Per worker: what a chunk's triangles reuse.
  struct ChunkScratch {
    ChunkScratch(PolygonCache& cache, std::size_t operands) : cache(cache), handover(operands) {}
    PolygonCache& cache;  ///< the thread's: shared by its ranges of chunks
    CutScratch cut;
    TraceScratch trace;
    SolidHandover handover;
    CutHandover cut_handover;
    std::vector<const Polygon*> partner_polys;
    std::vector<std::uint32_t> partner_operands;
    PieceWindings windings;  ///< of the current triangle's pieces
    Wnv front, back;
  };

  /// The touched triangles of operand o in curve slots first .. first +
  /// kChunk - 1, cut and classified into `out`. A piece with an edge on an
  /// input edge whose other triangle is untouched takes that triangle's
  /// winding numbers (solid_route.hpp, 4: nothing else comes near that edge,
  /// so the same argument holds); the others are handed over or traced.
  bool solve_chunk(std::uint32_t o, std::uint32_t first, ChunkScratch& cs, std::vector<OutputPolygon>& out,
                   const std::atomic<bool>& failed) const {
    cs.handover.clear();  // a chunk's result must not depend on the chunks before it
    const TriangleTree& tree = trees_.tree[o];
    for (std::size_t slot = first; slot < std::min(tree.size(), first + kChunk) && !failed.load(); ++slot) {
      const std::uint32_t id = trees_.begin[o] + tree.item(slot);
      if (!touched_[id]) continue;
      cs.cut.partners = partners_.of(id);
      cs.cache.reset_if_full(cs.cut.partners.size());
      const Polygon& t = cs.cache.get(id);
      const bool whole = cut_triangle(t, id, cs.cache, cs.cut) && cs.cut.pieces.size() == 1;
      cs.handover.begin_triangle(id, t, cs.cut.partners, grid_);
      // Every piece's winding numbers first (most from across input edges
      // and cut lines, classify_in_turn), then recorded and emitted in
      // order. They are exact, whichever way they are found, so the
      // handover's state and the output do not depend on the way.
      const std::vector<Piece>& pieces = cs.cut.pieces;
      if (!classify_in_turn(pieces, t, id, o, cs)) return false;
      for (std::size_t m = 0; m < pieces.size(); ++m) {
        const Polygon& f = pieces[m].poly;
        cs.windings.get(m, cs.front, cs.back);
        cs.handover.record(f, cs.front, cs.back);
        const Crossing c = ctx_.crossing(cs.front, cs.back);
        if (c.emitted) out.push_back(output_of(grid_, id, o, whole ? nullptr : &f, c));
      }
    }
    return true;
  }

  /// Piece f's winding numbers from across one of t's input edges (t:
  /// input triangle id, operand o): an untouched neighbour's component, else
  /// the handover from a neighbour's piece.
  bool known_across_input_edge(const Polygon& f, const Polygon& t, std::uint32_t id, std::uint32_t o,
                               SolidHandover& handover, Wnv& front, Wnv& back) const {
    const std::uint32_t via = untouched_neighbour_along(f, t, grid_.neighbors[id], touched_);
    if (via != kNoNeighbor) {
      component_w(via, front, back);
      front[o] = 0;
      back[o] = 1;
      return true;
    }
    return handover.find(f, front, back);
  }

  /// The pieces of touched triangle t, into cs.windings: first those known
  /// across t's input edges, then, spreading from the known pieces, their
  /// neighbours across cut lines (CutHandover::spread), tracing a piece only
  /// where nothing known reaches it. A triangle then costs one trace per
  /// group of pieces its cut lines cannot hand across (none, mostly: its
  /// input edges decide a piece), rather than one trace per piece its input
  /// edges do not decide, which on a finely cut triangle is most of them.
  bool classify_in_turn(const std::vector<Piece>& pieces, const Polygon& t, std::uint32_t id, std::uint32_t o,
                        ChunkScratch& cs) const {
    const std::size_t n = pieces.size();
    PieceWindings& pw = cs.windings;
    pw.reset(n, operands_);
    for (std::size_t m = 0; m < n; ++m)
      if (known_across_input_edge(pieces[m].poly, t, id, o, cs.handover, cs.front, cs.back))
        pw.store(m, cs.front, cs.back);
    if (pw.complete()) return true;
    // A coplanar partner blocks every cut line (CutHandover): the rest is traced.
    if (std::find(cs.cut.coplanar.begin(), cs.cut.coplanar.end(), 1) != cs.cut.coplanar.end())
      return trace_rest(pieces, id, o, cs);
    cs.partner_polys.clear();
    cs.partner_operands.clear();
    for (const std::uint32_t q : cs.cut.partners) {
      cs.partner_polys.push_back(&cs.cache.get(q));
      cs.partner_operands.push_back(trees_.operand_of(q));
    }
    cs.cut_handover.begin_triangle(t, cs.partner_polys, cs.partner_operands);
    return cs.cut_handover.spread(pieces, pw, [&](std::size_t m, Wnv& front, Wnv& back) {
      return trace_piece(pieces[m].poly, id, m, o, front, back, cs.trace);
    });
  }

  bool trace_piece(const Polygon& f, std::uint32_t id, std::size_t m, std::uint32_t o, Wnv& front, Wnv& back,
                   TraceScratch& sc) const {
    return classify_from_outside(tracer_, f, o, (std::uint64_t{id} << 20) ^ (m << 10), front, back, sc);
  }

  /// Traces the pieces still unknown in cs.windings: side by side when
  /// there are many (a face under a pile of coplanar-touching slivers would
  /// hold one thread; the values are exact, so the order does not matter).
  bool trace_rest(const std::vector<Piece>& pieces, std::uint32_t id, std::uint32_t o, ChunkScratch& cs) const {
    PieceWindings& pw = cs.windings;
    const std::size_t n = pieces.size();
    if (n - pw.order.size() < kParallelTraces) {
      for (std::size_t m = 0; m < n; ++m) {
        if (pw.known[m]) continue;
        if (!trace_piece(pieces[m].poly, id, m, o, cs.front, cs.back, cs.trace)) return false;
        pw.store(m, cs.front, cs.back);
      }
      return true;
    }
    std::atomic<bool> ok{true};
    tbb::this_task_arena::isolate([&] {  // waiting here runs only these pieces, not other chunks
      tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, 8), [&](const auto& r) {
        TraceScratch scratch;
        Wnv front, back;
        for (std::size_t m = r.begin(); m != r.end() && ok.load(std::memory_order_relaxed); ++m) {
          if (pw.known[m]) continue;
          if (!trace_piece(pieces[m].poly, id, m, o, front, back, scratch)) {
            ok = false;
            return;
          }
          const auto at = pw.w.begin() + static_cast<std::ptrdiff_t>(2 * operands_ * m);  // m's own slots
          std::copy(front.begin(), front.end(), at);
          std::copy(back.begin(), back.end(), at + static_cast<std::ptrdiff_t>(operands_));
        }
      });
    });
    if (!ok.load()) return false;
    for (std::size_t m = 0; m < n; ++m)
      if (!pw.known[m]) {
        pw.known[m] = 1;
        pw.order.push_back(static_cast<std::uint32_t>(m));
      }
    return true;
  }

  /// The winding numbers of untouched triangle id's component.
  void component_w(std::uint32_t id, Wnv& front, Wnv& back) const {
    const auto at = comp_w_.begin() + static_cast<std::ptrdiff_t>(2 * operands_ * comps_.index[id]);
    front.assign(at, at + static_cast<std::ptrdiff_t>(operands_));
    back.assign(at + static_cast<std::ptrdiff_t>(operands_), at + static_cast<std::ptrdiff_t>(2 * operands_));
  }

  const GridTriangles& grid_;
  const SolveContext& ctx_;
  const OperandTrees& trees_;
  const Partners& partners_;
  const std::atomic<bool>& stop_;  ///< abandon the run (solve_solid)
  std::size_t operands_;
  Tracer tracer_;
  FillVector<char> touched_;
  Components comps_;
  std::vector<int> comp_w_;
};

}  // namespace

std::optional<std::vector<OutputPolygon>> solve_solid(const GridTriangles& grid, const Box& box,
                                                      const SolveContext& ctx, const OperandTrees& trees,
                                                      const std::atomic<bool>* abandon, const Partners* found) {
  const std::atomic<bool> never{false};
  const std::atomic<bool>& stop = abandon ? *abandon : never;
  // 1. Which triangles another operand's triangles meet, and which.
  std::optional<Partners> own;
  if (!found) own = find_partners(grid, trees, grid.corners.size(), stop);
  const Partners& partners = found ? *found : *own;
  if (stop.load()) return std::nullopt;
  SolidSolver solver(grid, box, ctx, trees, partners, stop);
  std::vector<std::vector<OutputPolygon>> touched_out;
  if (!solver.classify_components() || !solver.solve_touched(touched_out)) return std::nullopt;
  return solver.output(std::move(touched_out));
}

std::optional<FillVector<KeptTriangle>> solid_untouched(const GridTriangles& grid, const Box& box,
                                                        const SolveContext& ctx, const OperandTrees& trees,
                                                        const Partners& partners, const std::atomic<bool>& stop) {
  SolidSolver solver(grid, box, ctx, trees, partners, stop);
  if (!solver.classify_components()) return std::nullopt;
  return solver.kept_untouched(solver.component_crossings());
}

}  // namespace ember::core
