// Step 4 of the mesh stage: ear clipping of a region (outer loop plus holes)
// with exact orientation tests in the region's plane (orient_in_plane, behind
// a floating-point filter). Holes are joined to the outer loop by a bridge
// that provably crosses nothing; an ear is clipped only when it has positive
// area and no other vertex lies in its closed triangle, so no zero-area
// triangle is ever produced. Anything unexpected answers false and the caller
// falls back to triangulating the region's pieces one by one.
#include "core/output/region_triangulation.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <optional>
#include <span>
#include <type_traits>

#include "core/output/loop_grid.hpp"
#include "core/output/output_vertices.hpp"
#include "core/output/regions.hpp"
#include "geometry/exact_order.hpp"

namespace ember::core {

namespace {

/// A region's vertices and its plane's orientation test.
struct Ctx {
  Ctx(const OutputVertices& verts, const Plane& plane) : verts(verts), in_plane(plane) {}
  const OutputVertices& verts;
  PlaneOrientation in_plane;
  const Point& pt(std::uint32_t i) const { return verts.exact[i]; }
  [[gnu::always_inline]] int orient(std::uint32_t a, std::uint32_t b, std::uint32_t c) const {
    return in_plane(pt(a), pt(b), pt(c));
  }
};

/// x strictly inside the angle at corner b of a loop running a -> b -> c
/// (region on the left).
bool inside_corner(const Ctx& k, std::uint32_t a, std::uint32_t b, std::uint32_t c, std::uint32_t x) {
  if (k.orient(a, b, c) > 0) return k.orient(a, b, x) > 0 && k.orient(b, c, x) > 0;
  return !(k.orient(a, b, x) <= 0 && k.orient(b, c, x) <= 0);
}

/// x lies on the closed segment [s, t] (x collinear with it).
bool on_segment(const Ctx& k, std::uint32_t s, std::uint32_t t, std::uint32_t x) {
  const Point &ps = k.pt(s), &pt = k.pt(t), &px = k.pt(x);
  for (int axis = 0; axis < 3; ++axis) {
    const int a = compare_coord(px, ps, axis), b = compare_coord(px, pt, axis);
    if (a * b > 0) return false;
  }
  return true;
}

/// The closed segments [p, q] and [s, t] share a point.
bool segments_meet(const Ctx& k, std::uint32_t p, std::uint32_t q, std::uint32_t s, std::uint32_t t) {
  const int o1 = k.orient(p, q, s), o2 = k.orient(p, q, t), o3 = k.orient(s, t, p), o4 = k.orient(s, t, q);
  if (o1 * o2 < 0 && o3 * o4 < 0) return true;
  return (o1 == 0 && on_segment(k, p, q, s)) || (o2 == 0 && on_segment(k, p, q, t)) ||
         (o3 == 0 && on_segment(k, s, t, p)) || (o4 == 0 && on_segment(k, s, t, q));
}

/// Loops of the region's alive boundary edges, each as its vertices in order.
bool collect_loops(const Regions& regions, std::uint32_t region, std::vector<std::vector<std::uint32_t>>& loops) {
  const std::uint32_t first = regions.edge_begin[region], last = regions.edge_begin[region + 1];
  std::vector<char> seen(last - first, 0);
  for (std::uint32_t s = first; s < last; ++s) {
    if (!regions.edges[s].alive || seen[s - first]) continue;
    std::vector<std::uint32_t> loop;
    std::uint32_t e = s;
    do {
      const BoundaryEdge& be = regions.edges[e];
      if (e < first || e >= last || !be.alive || seen[e - first]) return false;
      seen[e - first] = 1;
      loop.push_back(be.from);
      e = be.next;
    } while (e != s);
    if (loop.size() < 3) return false;
    loops.push_back(std::move(loop));
  }
  return true;
}

/// The region's loop when it has exactly three edges, all alive, forming one
/// cycle: the loop collect_loops would return (starting at the first edge),
/// without its allocations. Most regions of a curved result are such triangles.
std::optional<std::array<std::uint32_t, 3>> single_triangle_loop(const Regions& regions, std::uint32_t region) {
  const std::uint32_t first = regions.edge_begin[region], last = regions.edge_begin[region + 1];
  if (last - first != 3) return std::nullopt;
  std::array<std::uint32_t, 3> t{};
  std::uint32_t e = first;
  for (int i = 0; i < 3; ++i) {
    if (e < first || e >= last || !regions.edges[e].alive) return std::nullopt;
    t[static_cast<std::size_t>(i)] = regions.edges[e].from;
    e = regions.edges[e].next;
  }
  if (e != first) return std::nullopt;
  return t;
}

/// +1 for a counter-clockwise loop, -1 clockwise, 0 if undecidable here: the
/// turn at its lexicographically smallest vertex, which is a corner of the
/// loop's convex hull. A loop may pass that vertex more than once (regions
/// touching themselves there); each pass is then a corner whose wedge lies in
/// a half-plane, so all passes turn the same way and any of them decides.
int loop_orientation(const Ctx& k, const std::vector<std::uint32_t>& loop) {
  std::size_t m = 0;
  for (std::size_t i = 1; i < loop.size(); ++i)
    if (compare_lex(k.pt(loop[i]), k.pt(loop[m])) < 0) m = i;
  const std::size_t n = loop.size();
  int turn = 0;
  for (std::size_t i = 0; i < n; ++i) {
    if (loop[i] != loop[m]) continue;
    const int o = k.orient(loop[(i + n - 1) % n], loop[i], loop[(i + 1) % n]);
    if (o == 0 || (turn != 0 && o != turn)) return 0;
    turn = o;
  }
  return turn;
}

double approx_dist2(const Ctx& k, std::uint32_t a, std::uint32_t b) {
  const auto &fa = k.pt(a).f, &fb = k.pt(b).f;
  return (fa[0] - fb[0]) * (fa[0] - fb[0]) + (fa[1] - fb[1]) * (fa[1] - fb[1]) + (fa[2] - fb[2]) * (fa[2] - fb[2]);
}

/// Joins `hole` into `outer` with a bridge from the hole's lexicographically
/// largest vertex to the nearest outer vertex it sees. False if none found.
bool bridge_hole(const Ctx& k, std::vector<std::uint32_t>& outer, const std::vector<std::uint32_t>& hole,
                 std::span<const std::vector<std::uint32_t>> others) {
  const std::size_t hn = hole.size();
  std::size_t hi = 0;
  for (std::size_t i = 1; i < hn; ++i)
    if (compare_lex(k.pt(hole[i]), k.pt(hole[hi])) > 0) hi = i;
  const std::uint32_t h = hole[hi], hp = hole[(hi + hn - 1) % hn], hx = hole[(hi + 1) % hn];
  std::vector<std::size_t> cand(outer.size());
  for (std::size_t i = 0; i < outer.size(); ++i) cand[i] = i;
  std::sort(cand.begin(), cand.end(), [&](std::size_t x, std::size_t y) {
    const double dx = approx_dist2(k, h, outer[x]), dy = approx_dist2(k, h, outer[y]);
    return dx < dy || (dx == dy && x < y);
  });
  auto crosses_loop = [&](const std::vector<std::uint32_t>& loop, std::uint32_t p) {
    for (std::size_t i = 0; i < loop.size(); ++i) {
      const std::uint32_t s = loop[i], t = loop[(i + 1) % loop.size()];
      if (s == h || t == h || s == p || t == p) continue;  // corners are checked by the cone tests
      if (segments_meet(k, h, p, s, t)) return true;
    }
    return false;
  };
  const std::size_t on = outer.size();
  for (const std::size_t i : cand) {
    const std::uint32_t p = outer[i];
    if (p == h) {  // the hole touches the outer loop here: splice it in at the shared vertex
      std::vector<std::uint32_t> merged(outer.begin(), outer.begin() + static_cast<std::ptrdiff_t>(i) + 1);
      for (std::size_t j = 1; j <= hn; ++j) merged.push_back(hole[(hi + j) % hn]);
      merged.insert(merged.end(), outer.begin() + static_cast<std::ptrdiff_t>(i) + 1, outer.end());
      outer = std::move(merged);
      return true;
    }
    if (!inside_corner(k, outer[(i + on - 1) % on], p, outer[(i + 1) % on], h)) continue;
    if (!inside_corner(k, hp, h, hx, p)) continue;
    // The open segment may not pass through any other vertex equal to p or h.
    if (crosses_loop(outer, p) || crosses_loop(hole, p)) continue;
    bool blocked = false;
    for (const auto& o : others) blocked = blocked || crosses_loop(o, p);
    if (blocked) continue;
    std::vector<std::uint32_t> merged(outer.begin(), outer.begin() + static_cast<std::ptrdiff_t>(i) + 1);
    for (std::size_t j = 0; j <= hn; ++j) merged.push_back(hole[(hi + j) % hn]);
    merged.insert(merged.end(), outer.begin() + static_cast<std::ptrdiff_t>(i), outer.end());
    outer = std::move(merged);
    return true;
  }
  return false;
}

}  // namespace

namespace {

/// One vertex of a loop being clipped: its neighbours still in the loop,
/// and the version of its newest queue entry (older entries are stale).
struct EarNode {
  std::uint32_t prev = 0, next = 0, version = 0;
  bool removed = false;
};

/// A queued ear: the clipper takes the best quality first, the lowest
/// vertex on ties.
struct EarCandidate {
  double q;
  std::uint32_t node, version;
  bool operator<(const EarCandidate& o) const { return q != o.q ? q < o.q : node > o.node; }
};

/// The ears waiting to be tried, best first (EarCandidate's order): a heap
/// (std::priority_queue's push_heap / pop_heap, so the ears come in the
/// same order whatever memory holds it) in `heap`, with room for 2 n
/// entries (it starts with n and each clip pops at least one and pushes
/// two, n - 3 times). A vertex queued again makes its older entry stale.
class HeapQueue {
 public:
  HeapQueue(std::span<EarNode> node, std::span<EarCandidate> heap) : node_(node), heap_(heap) {}
  void push(std::uint32_t b, double q) {
    heap_[queued_++] = {q, b, ++node_[b].version};
    std::push_heap(heap_.begin(), heap_.begin() + static_cast<std::ptrdiff_t>(queued_));
  }
  /// The best vertex queued and not removed since, taken off the queue;
  /// nullopt when none is left.
  std::optional<std::uint32_t> pop() {
    while (queued_ > 0) {
      std::pop_heap(heap_.begin(), heap_.begin() + static_cast<std::ptrdiff_t>(queued_));
      const EarCandidate c = heap_[--queued_];
      if (!node_[c.node].removed && c.version == node_[c.node].version) return c.node;
    }
    return std::nullopt;
  }

 private:
  std::span<EarNode> node_;
  std::span<EarCandidate> heap_;
  std::size_t queued_ = 0;
};

/// The same queue for short loops (at most kScanLoop vertices): each
/// vertex's newest quality and whether it is queued, the best found by a
/// scan (the heap's order: highest quality, then lowest vertex). A heap's
/// pushes and pops cost more than scanning a handful of vertices (the
/// direct route's faces: 4-6 vertices mostly).
class ScanQueue {
 public:
  static constexpr std::size_t kScanLoop = 16;
  explicit ScanQueue(std::span<const EarNode> node) : node_(node) {}
  void push(std::uint32_t b, double q) {
    q_[b] = q;
    queued_[b] = true;
  }
  std::optional<std::uint32_t> pop() {
    std::optional<std::uint32_t> best;
    for (std::uint32_t i = 0; i < node_.size(); ++i)
      if (queued_[i] && !node_[i].removed && (!best || q_[i] > q_[*best])) best = i;
    if (best) queued_[*best] = false;
    return best;
  }

 private:
  std::span<const EarNode> node_;
  std::array<double, kScanLoop> q_{};
  std::array<bool, kScanLoop> queued_{};
};

/// The box of an ear's corners (their double approximations), worked out
/// once per ear test rather than once per vertex tested against it.
struct EarBox {
  std::array<double, 3> lo, hi;
};

/// An EarBox with its slack worked out too, for long loops, whose ears are
/// each tested against many vertices: a vertex within the box's magnitude
/// m (|x| <= m) has slack 2^-40 m, so it is compared against lo - 2^-40 m
/// and hi + 2^-40 m precomputed (the same comparisons as box_excludes'
/// general formula); short loops test an ear against few vertices and
/// would pay the set-up for nothing.
struct SlackedEarBox : EarBox {
  std::array<double, 3> m, slo, shi;
};

/// The vertices an ear a b c must not hold, offered to f until it says
/// true: every vertex now in the loop but a, b and c, walking round it.
struct WalkRound {
  using Box = EarBox;
  void removed(std::uint32_t) const {}
  template <typename F>
  [[gnu::always_inline]] bool any(std::span<const EarNode> node, std::uint32_t a, std::uint32_t, std::uint32_t c,
                                  const EarBox&, F&& f) const {
    for (std::uint32_t x = node[c].next; x != a; x = node[x].next)
      if (f(x)) return true;
    return false;
  }
};

/// The same for long loops, through a LoopGrid of the loop's vertices (each
/// walk had cost O(n)): those in the cells of the ear's box (clipped
/// vertices leave their cells); the caller's double filter and exact tests
/// decide as before, so the same ears are clipped.
struct FromGrid {
  using Box = SlackedEarBox;
  LoopGrid& grid;
  /// A clipped vertex leaves its cell, so later ears no longer offer it.
  void removed(std::uint32_t x) const { grid.remove(x); }
  template <typename F>
  bool any(std::span<const EarNode>, std::uint32_t a, std::uint32_t b, std::uint32_t c, const EarBox& box,
           F&& f) const {
    return grid.any(box.lo, box.hi, [&](std::uint32_t x) { return x != a && x != b && x != c && f(x); });
  }
};

/// The ear clipping of `loop` with working memory `node` (one per vertex)
/// and an ear queue (HeapQueue or ScanQueue over the same nodes).
template <typename Others, typename Queue>
bool clip_ears(const Ctx& k, std::span<const std::uint32_t> loop, std::span<EarNode> node, Queue& queue,
               const Others& others, std::vector<std::array<std::uint32_t, 3>>& out) {
  using Box = typename Others::Box;
  constexpr bool kSlacked = std::is_same_v<Box, SlackedEarBox>;
  const std::size_t before = out.size();
  const std::uint32_t size = static_cast<std::uint32_t>(loop.size());
  std::size_t n = size;
  for (std::uint32_t i = 0; i < size; ++i) node[i] = {i == 0 ? size - 1 : i - 1, i + 1 == size ? 0 : i + 1, 0, false};
  // Conservative double boxes: Point::f errs < 8 ulp; 2^-40 relative covers it.
  auto box_excludes = [&](const Box& box, std::size_t x) {
    for (int axis = 0; axis < 3; ++axis) {
      const double lo = box.lo[axis], hi = box.hi[axis], fx = k.pt(loop[x]).f[axis];
      if constexpr (kSlacked) {
        if (std::fabs(fx) <= box.m[axis]) {
          if (fx < box.slo[axis] || fx > box.shi[axis]) return true;
          continue;
        }
      }
      const double slack = 0x1p-40 * std::max({std::fabs(lo), std::fabs(hi), std::fabs(fx)});
      if (fx < lo - slack || fx > hi + slack) return true;
    }
    return false;
  };
  auto is_ear = [&](std::uint32_t b) __attribute__((always_inline)) {
    const std::uint32_t a = node[b].prev, c = node[b].next;
    if (k.orient(loop[a], loop[b], loop[c]) <= 0) return false;
    Box box;
    for (int axis = 0; axis < 3; ++axis) {
      const double fa = k.pt(loop[a]).f[axis], fb = k.pt(loop[b]).f[axis], fc = k.pt(loop[c]).f[axis];
      box.lo[axis] = std::min({fa, fb, fc});
      box.hi[axis] = std::max({fa, fb, fc});
      if constexpr (kSlacked) {
        box.m[axis] = std::max(std::fabs(box.lo[axis]), std::fabs(box.hi[axis]));
        box.slo[axis] = box.lo[axis] - 0x1p-40 * box.m[axis];
        box.shi[axis] = box.hi[axis] + 0x1p-40 * box.m[axis];
      }
    }
    // x, another vertex of the loop now, lies in the closed triangle a b c.
    return !others.any(
        node, a, b, c, box, [&](std::uint32_t x) __attribute__((always_inline)) {
          const std::uint32_t v = loop[x];
          if (v == loop[a] || v == loop[b] || v == loop[c] || box_excludes(box, x)) return false;
          return k.orient(loop[a], loop[b], v) >= 0 && k.orient(loop[b], loop[c], v) >= 0 &&
                 k.orient(loop[c], loop[a], v) >= 0;
        });
  };
  // Best-shaped ear first (Manifold clips sharpest ears first for the same
  // reason): an ear at a nearly straight vertex would be a sliver, whose tiny
  // height the rounding to double and a later re-quantization can flip. The
  // shape is judged in doubles; validity is always decided exactly.
  auto quality = [&](std::uint32_t b) {
    const auto &fa = k.pt(loop[node[b].prev]).f, &fb = k.pt(loop[b]).f, &fc = k.pt(loop[node[b].next]).f;
    const double ux = fb[0] - fa[0], uy = fb[1] - fa[1], uz = fb[2] - fa[2];
    const double vx = fc[0] - fb[0], vy = fc[1] - fb[1], vz = fc[2] - fb[2];
    const double wx = fa[0] - fc[0], wy = fa[1] - fc[1], wz = fa[2] - fc[2];
    const double cx = uy * vz - uz * vy, cy = uz * vx - ux * vz, cz = ux * vy - uy * vx;
    const double l2 = ux * ux + uy * uy + uz * uz + vx * vx + vy * vy + vz * vz + wx * wx + wy * wy + wz * wz;
    return l2 > 0 ? std::sqrt(cx * cx + cy * cy + cz * cz) / l2 : 0.0;
  };
  auto push = [&](std::uint32_t b) { queue.push(b, quality(b)); };
  auto push_all = [&] {
    for (std::uint32_t i = 0; i < size; ++i)
      if (!node[i].removed) push(i);
  };
  push_all();
  bool refilled = false;
  while (n > 3) {
    const std::optional<std::uint32_t> next = queue.pop();
    if (!next) {
      if (refilled) {  // a whole round without a valid ear
        out.resize(before);
        return false;
      }
      push_all();
      refilled = true;
      continue;
    }
    if (!is_ear(*next)) continue;
    const std::uint32_t b = *next, a = node[b].prev, d = node[b].next;
    out.push_back({loop[a], loop[b], loop[d]});
    node[a].next = d;
    node[d].prev = a;
    node[b].removed = true;
    others.removed(b);
    --n;
    push(a);
    push(d);
    refilled = false;
  }
  std::uint32_t cur = 0;
  while (node[cur].removed) ++cur;
  const std::uint32_t a = node[cur].prev, c = node[cur].next;
  if (k.orient(loop[a], loop[cur], loop[c]) <= 0) {
    out.resize(before);
    return false;
  }
  out.push_back({loop[a], loop[cur], loop[c]});
  return true;
}

}  // namespace

bool triangulate_loop(std::span<const std::uint32_t> loop, const Plane& plane, const OutputVertices& verts,
                      std::vector<std::array<std::uint32_t, 3>>& out, std::size_t grid_from) {
  const Ctx k{verts, plane};
  // Most loops are small (the direct route's faces: a handful of vertices):
  // their working memory lives on the stack, which saved the route a third
  // of its ear clipping's instructions in allocations.
  constexpr std::size_t kSmall = ScanQueue::kScanLoop;
  if (loop.size() <= kSmall && loop.size() < grid_from) {
    std::array<EarNode, kSmall> node;
    ScanQueue queue{std::span<const EarNode>(node.data(), loop.size())};
    return clip_ears(k, loop, node, queue, WalkRound{}, out);
  }
  std::vector<EarNode> node(loop.size());
  std::vector<EarCandidate> heap(2 * loop.size());
  HeapQueue queue(node, heap);
  if (loop.size() < grid_from) return clip_ears(k, loop, node, queue, WalkRound{}, out);
  LoopGrid grid(loop.size(), [&](std::size_t i) -> const std::array<double, 3>& { return k.pt(loop[i]).f; });
  return clip_ears(k, loop, node, queue, FromGrid{grid}, out);
}

bool triangulate_region(const Regions& regions, std::uint32_t region, const OutputVertices& verts,
                        std::vector<std::array<std::uint32_t, 3>>& out) {
  const Plane& plane = regions.regions[region].plane;
  const Ctx k{verts, plane};
  // Most regions of a curved surface are one triangle: no ear search needed.
  const auto emit_triangle = [&](const std::array<std::uint32_t, 3>& t) {
    if (k.orient(t[0], t[1], t[2]) <= 0) return false;
    out.push_back({t[2], t[0], t[1]});  // the rotation the ear clipper ends with
    return true;
  };
  if (const std::optional<std::array<std::uint32_t, 3>> t = single_triangle_loop(regions, region))
    return emit_triangle(*t);
  std::vector<std::vector<std::uint32_t>> loops;
  if (!collect_loops(regions, region, loops)) return false;
  if (loops.size() == 1 && loops[0].size() == 3) return emit_triangle({loops[0][0], loops[0][1], loops[0][2]});
  std::vector<std::uint32_t> outer;
  std::vector<std::vector<std::uint32_t>> holes;
  for (auto& loop : loops) {
    const int o = loop_orientation(k, loop);
    if (o == 0) return false;
    if (o > 0) {
      if (!outer.empty()) return false;  // several outer loops: not one polygon with holes
      outer = std::move(loop);
    } else {
      holes.push_back(std::move(loop));
    }
  }
  if (outer.empty()) return false;
  return triangulate_with_holes(std::move(outer), std::move(holes), plane, verts, out);
}

bool triangulate_with_holes(std::vector<std::uint32_t> outer, std::vector<std::vector<std::uint32_t>> holes,
                            const Plane& plane, const OutputVertices& verts,
                            std::vector<std::array<std::uint32_t, 3>>& out) {
  const Ctx k{verts, plane};
  // Holes in decreasing order of their lexicographically largest vertex (the
  // order of Eberly's hole bridging): the ray from that vertex in the
  // direction of the order meets only the outer loop and holes already
  // joined to it, so a visible outer vertex exists even where holes sit in a
  // row and would hide each other's bridges.
  if (holes.size() > 1) {
    std::vector<std::pair<std::uint32_t, std::size_t>> top(holes.size());  // (largest vertex, hole)
    for (std::size_t i = 0; i < holes.size(); ++i) {
      top[i] = {holes[i][0], i};
      for (const std::uint32_t v : holes[i])
        if (compare_lex(k.pt(v), k.pt(top[i].first)) > 0) top[i].first = v;
    }
    std::stable_sort(top.begin(), top.end(),
                     [&](const auto& a, const auto& b) { return compare_lex(k.pt(a.first), k.pt(b.first)) > 0; });
    std::vector<std::vector<std::uint32_t>> sorted(holes.size());
    for (std::size_t i = 0; i < top.size(); ++i) sorted[i] = std::move(holes[top[i].second]);
    holes = std::move(sorted);
  }
  for (std::size_t i = 0; i < holes.size(); ++i) {
    const std::span<const std::vector<std::uint32_t>> rest(holes.data() + i + 1, holes.size() - i - 1);
    if (!bridge_hole(k, outer, holes[i], rest)) return false;
  }
  return triangulate_loop(outer, plane, verts, out);
}

int loop_orientation_in_plane(const std::vector<std::uint32_t>& loop, const Plane& plane, const OutputVertices& verts) {
  return loop_orientation(Ctx{verts, plane}, loop);
}

int locate_in_loop(const std::vector<std::uint32_t>& loop, std::uint32_t x, const Plane& plane,
                   const OutputVertices& verts) {
  // Crossings of the ray from x along +u in the projection along the
  // plane's dominant axis (one-to-one on the plane), half-open in v.
  const int drop = dominant_axis(plane), u = (drop + 1) % 3, v = (drop + 2) % 3;
  const Point& p = verts.exact[x];
  bool inside = false;
  for (std::size_t i = 0, n = loop.size(); i < n; ++i) {
    const Point &a = verts.exact[loop[i]], &b = verts.exact[loop[(i + 1) % n]];
    const int va = compare_coord(a, p, v), vb = compare_coord(b, p, v);
    if (va * vb > 0) continue;  // both above or both below x
    const int o = orient2d_dropped(a, b, p, drop);
    if (o == 0 && va * vb <= 0 && compare_coord(a, p, u) * compare_coord(b, p, u) <= 0) return -1;  // on the edge
    const bool a_above = va > 0, b_above = vb > 0;
    if (a_above == b_above) continue;
    // The edge crosses the line through x: to the right of x iff x is left
    // of an upward edge or right of a downward one.
    if (b_above ? o > 0 : o < 0) inside = !inside;
  }
  return inside ? 1 : 0;
}

}  // namespace ember::core
