// The solid path (solid_path.hpp): broad phase on per-operand triangle
// trees, polygon-local BSPs of the touched triangles, classification by
// traces from outside, untouched triangles by components.
#include "core/solid_path.hpp"

#include <tbb/blocked_range.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_invoke.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <atomic>
#include <bit>
#include <deque>
#include <numeric>

#include "core/pieces.hpp"
#include "core/solid_handover.hpp"
#include "core/solid_trace.hpp"
#include "core/triangle_tree.hpp"

namespace ember::core {

namespace {

/// The meeting pairs, both ways, grouped by triangle: partners of id are
/// ids[begin[id] .. begin[id + 1]), ascending.
struct Partners {
  std::vector<std::uint32_t> begin, ids;
  bool touched(std::uint32_t id) const { return begin[id + 1] > begin[id]; }
  std::span<const std::uint32_t> of(std::uint32_t id) const { return {ids.data() + begin[id], begin[id + 1] - begin[id]}; }
};

using PairSink = tbb::enumerable_thread_specific<std::vector<std::pair<std::uint32_t, std::uint32_t>>>;

/// Collects every pair of A x B that meets (boxes first, then exactly:
/// triangles_meet), in subtrees a of A at depth da and b of B at depth db.
void meeting_pairs(const GridTriangles& grid, const TriangleTree& A, std::uint32_t a_base, std::size_t a, int da,
                   const TriangleTree& B, std::uint32_t b_base, std::size_t b, int db, PairSink& sink) {
  if (!overlap(A.node(a), B.node(b))) return;
  const bool a_leaf = da == A.depth(), b_leaf = db == B.depth();
  if (a_leaf && b_leaf) {
    const std::size_t ab = A.leaf_slots(a).first, bb = B.leaf_slots(b).first;
    if (ab >= A.size() || bb >= B.size()) return;  // empty leaves (their boxes meet nothing anyway)
    // a's triangles whose boxes meet b's node box, eight at a time.
    for (unsigned near = A.overlap_mask(a, B.node(b)); near != 0; near &= near - 1) {
      const std::size_t i = ab + static_cast<std::size_t>(std::countr_zero(near));
      const Box32 box = A.box(i);
      const std::uint32_t ia = a_base + A.item(i);
      const std::array<IntPoint, 3>& ta = grid.corners[ia];
      unsigned m = B.overlap_mask(b, box);
      if (m == 0) continue;
      // Most box pairs have one triangle wholly beside the other's plane,
      // which three exact dot products tell without the full test's set-up.
      const std::array<std::int64_t, 3> na = grid_normal(ta[0], ta[1], ta[2]);
      for (; m != 0; m &= m - 1) {
        const std::uint32_t ib = b_base + B.item(bb + static_cast<std::size_t>(std::countr_zero(m)));
        const std::array<IntPoint, 3>& tb = grid.corners[ib];
        if (!beside_plane(ta, na, tb) && apart_triangles_meet(ta, na, tb, grid_normal(tb[0], tb[1], tb[2])))
          sink.local().emplace_back(ia, ib);
      }
    }
    return;
  }
  // Descend the side with more levels below (node sizes stay alike); large
  // subtrees as parallel tasks.
  constexpr int kParallelLevels = 6;
  const bool split_a = !a_leaf && (b_leaf || A.depth() - da >= B.depth() - db);
  const auto child = [&](int c) {
    if (split_a) {
      meeting_pairs(grid, A, a_base, 2 * a + 1 + c, da + 1, B, b_base, b, db, sink);
    } else {
      meeting_pairs(grid, A, a_base, a, da, B, b_base, 2 * b + 1 + c, db + 1, sink);
    }
  };
  if ((split_a ? A.depth() - da : B.depth() - db) >= kParallelLevels) {
    tbb::parallel_invoke([&] { child(0); }, [&] { child(1); });
  } else {
    child(0);
    child(1);
  }
}

/// Broad and narrow phase: the meeting pairs of triangles of different
/// operands. Deterministic (sorted), whatever the schedule.
Partners find_partners(const GridTriangles& grid, const OperandTrees& trees, std::size_t n) {
  PairSink sink;
  const std::size_t operands = trees.tree.size();
  for (std::size_t a = 0; a < operands; ++a)
    for (std::size_t b = a + 1; b < operands; ++b) {
      const TriangleTree &A = trees.tree[a], &B = trees.tree[b];
      if (!A.empty() && !B.empty()) meeting_pairs(grid, A, trees.begin[a], 0, 0, B, trees.begin[b], 0, 0, sink);
    }
  // Counting sort by triangle, then each list ascending (lists are short,
  // and the result does not depend on the order pairs were found in).
  Partners p;
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

/// Built polygons of the triangles near the ones being processed, by id:
/// a touched triangle's partners are mostly the previous one's (triangles go
/// in Morton order), so each is built about once per chunk. References stay
/// valid until reset().
class PolygonCache {
 public:
  explicit PolygonCache(const GridTriangles& grid) : grid_(grid) { slots_.assign(1024, kEmpty); }
  const Polygon& get(std::uint32_t id) {
    std::size_t h = (id * 0x9e3779b1u) & (slots_.size() - 1);
    for (; slots_[h].first != kNone; h = (h + 1) & (slots_.size() - 1))
      if (slots_[h].first == id) return pool_[slots_[h].second];
    if (used_ == pool_.size()) pool_.emplace_back();
    const std::array<IntPoint, 3>& c = grid_.corners[id];
    assign_triangle(c[0], c[1], c[2], pool_[used_]);  // a soup triangle has area
    slots_[h] = {id, static_cast<std::uint32_t>(used_)};
    if (2 * ++used_ > slots_.size()) grow();
    return pool_[used_ - 1];
  }
  const std::array<IntPoint, 3>& corners(std::uint32_t id) const { return grid_.corners[id]; }
  /// Forgets everything (buffers are kept) once the cache holds far more
  /// than the next triangle needs (`partners` + itself).
  void reset_if_full(std::size_t partners) {
    if (used_ < 256 + 2 * partners) return;
    std::fill(slots_.begin(), slots_.end(), kEmpty);
    used_ = 0;
  }

 private:
  static constexpr std::uint32_t kNone = UINT32_MAX;
  static constexpr std::pair<std::uint32_t, std::uint32_t> kEmpty{kNone, 0};
  void grow() {
    std::vector<std::pair<std::uint32_t, std::uint32_t>> old(2 * slots_.size(), kEmpty);
    old.swap(slots_);
    for (const auto& e : old) {
      if (e.first == kNone) continue;
      std::size_t h = (e.first * 0x9e3779b1u) & (slots_.size() - 1);
      while (slots_[h].first != kNone) h = (h + 1) & (slots_.size() - 1);
      slots_[h] = e;
    }
  }
  const GridTriangles& grid_;
  std::vector<std::pair<std::uint32_t, std::uint32_t>> slots_;
  std::deque<Polygon> pool_;  ///< stable references
  std::size_t used_ = 0;
};

/// A piece's conservative box (approx_bounds).
struct PieceBox {
  std::array<double, 3> lo, hi;
};
PieceBox piece_box(const Polygon& p) {
  PieceBox b;
  approx_bounds(p, b.lo, b.hi);
  return b;
}
bool apart(const PieceBox& a, const PieceBox& b) {
  for (int i = 0; i < 3; ++i)
    if (a.hi[i] < b.lo[i] || b.hi[i] < a.lo[i]) return true;
  return false;
}

/// Scratch of the polygon-local BSP of one triangle.
struct CutScratch {
  std::vector<PieceBox> boxes;  ///< per piece
  std::span<const std::uint32_t> partners;
  std::vector<Piece> pieces, next;
  std::vector<std::int8_t> other_signs, signs;
  std::vector<Plane> cons;
  Polygon neg, pos;
};

/// Below this many pieces a partner's cut runs piece by piece.
constexpr std::size_t kParallelCut = 256;

/// The transverse cut of cut_triangle by partner o over pieces 0 .. n - 1 at
/// once: the pieces that o's plane splits are split in parallel, then the
/// halves are put in place in piece order, as the serial loop does (each
/// piece is cut by o on its own, and the new halves are not cut by o again).
/// For a large face under a pile of slivers (EMBER case 582: 3,000 partners,
/// 4,400 pieces), whose cuts would otherwise hold one thread.
void split_pieces_in_parallel(CutScratch& cs, std::size_t n, const Plane& support, const Polygon& o,
                              const PieceBox& ob) {
  struct Split {
    std::size_t i;
    Polygon neg, pos;
  };
  tbb::enumerable_thread_specific<std::vector<Split>> found;
  tbb::this_task_arena::isolate([&] {  // waiting here runs only these pieces
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, 64), [&](const tbb::blocked_range<std::size_t>& r) {
      std::vector<std::int8_t> signs;
      std::vector<Plane> cons;
      Polygon neg, pos;
      std::vector<Split>& local = found.local();
      for (std::size_t i = r.begin(); i != r.end(); ++i)
        if (!apart(cs.boxes[i], ob) &&
            split_by_transverse(cs.pieces[i].poly, support, o, cs.other_signs, signs, cons, neg, pos))
          local.push_back({i, std::move(neg), std::move(pos)});
    });
  });
  std::vector<Split> splits;
  for (std::vector<Split>& local : found)
    for (Split& sp : local) splits.push_back(std::move(sp));
  std::sort(splits.begin(), splits.end(), [](const Split& a, const Split& b) { return a.i < b.i; });
  for (Split& sp : splits) {
    cs.pieces[sp.i].poly = std::move(sp.neg);
    cs.pieces.push_back({std::move(sp.pos)});
    cs.boxes[sp.i] = piece_box(cs.pieces[sp.i].poly);
    cs.boxes.push_back(piece_box(cs.pieces.back().poly));
  }
}

/// t's pieces (Section 4.3 with closed operands and no box): what lower-id
/// coplanar partners cover is cut away and left to them (Fig. 8), then every
/// transverse partner touching t's plane cuts along its plane (C3). Higher-id
/// coplanar partners need no cut: their edges continue into triangles of
/// their closed operand that leave the plane, whose C3 cuts separate where
/// their coverage changes. Returns false if a partner covered part of t.
bool cut_triangle(const Polygon& t, std::uint32_t id, PolygonCache& cache, CutScratch& cs) {
  cs.pieces.resize(1);
  cs.pieces[0].poly = t;
  bool untouched = true;
  for (auto it = cs.partners.rbegin(); it != cs.partners.rend(); ++it) {  // nearest lower ids first
    if (*it >= id) continue;
    const Polygon& o = cache.get(*it);
    if (!coplanar(t.support, o.support)) continue;
    cs.next.clear();
    for (Piece& p : cs.pieces) {
      if (!coplanar_overlap(p.poly, o)) {
        cs.next.push_back(std::move(p));
        continue;
      }
      for (const Plane& e : o.edges) {  // the parts outside o stay
        if (clip(p.poly, e, cs.neg, cs.pos) != ClipSide::Both) continue;
        cs.next.push_back({std::move(cs.pos)});
        std::swap(p.poly, cs.neg);
      }
      untouched = false;
    }
    std::swap(cs.pieces, cs.next);
    if (cs.pieces.empty()) return false;
  }
  // Pieces skip partners their boxes are apart from (a sliver cut by many
  // partners along its length would test every piece against every one).
  cs.boxes.clear();
  for (const Piece& p : cs.pieces) cs.boxes.push_back(piece_box(p.poly));
  for (const std::uint32_t q : cs.partners) {
    const Polygon& o = cache.get(q);
    if (coplanar(t.support, o.support) || !touches_plane(cache.corners(q), t.support, cs.other_signs)) continue;
    const PieceBox ob = piece_box(o);
    const std::size_t n = cs.pieces.size();
    if (n >= kParallelCut) {
      split_pieces_in_parallel(cs, n, t.support, o, ob);
      continue;
    }
    for (std::size_t i = 0; i < n; ++i) {
      if (apart(cs.boxes[i], ob)) continue;
      cut_by_transverse(cs.pieces, i, t.support, o, cs.other_signs, cs.signs, cs.cons, cs.neg, cs.pos);
      if (cs.pieces.size() == cs.boxes.size()) continue;
      cs.boxes[i] = piece_box(cs.pieces[i].poly);
      cs.boxes.push_back(piece_box(cs.pieces.back().poly));
    }
  }
  return untouched;
}

/// The output form of t whole (unbuilt), or of one of its pieces.
OutputPolygon output_of(const SoupPolygon& t, const Polygon* piece, bool flip) {
  OutputPolygon out;
  if (piece) out.vertices.assign(piece->vertices.begin(), piece->vertices.end());
  out.corners = t.corners;
  out.id = t.id;
  out.operand = t.operand;
  out.flip = flip;
  out.whole_piece = !piece;
  return out;
}

/// The untouched triangles joined across manifold edges: roots (each
/// component's smallest id, ascending) and, per untouched triangle, its
/// component's index in `roots`.
struct Components {
  std::vector<std::uint32_t> roots;
  std::vector<std::uint32_t> index;
};

Components untouched_components(const GridTriangles& grid, const std::vector<char>& touched) {
  std::vector<char> untouched(touched.size());
  for (std::size_t i = 0; i < touched.size(); ++i) untouched[i] = !touched[i];
  Components c;
  c.index = neighbour_components(grid, untouched);
  // Roots come first in id order: each becomes its component's index, which
  // the later members of the component then read.
  for (std::uint32_t i = 0; i < c.index.size(); ++i) {
    if (!untouched[i]) continue;
    if (c.index[i] == i) {
      c.index[i] = static_cast<std::uint32_t>(c.roots.size());
      c.roots.push_back(i);
    } else {
      c.index[i] = c.index[c.index[i]];
    }
  }
  return c;
}

/// An untouched triangle across one of t's input edges along which piece f
/// has an edge (of positive length: f is strictly convex), or kNoNeighbor.
/// f's edges on t's edges keep t's edge planes (clip copies them).
std::uint32_t untouched_neighbour_along(const Polygon& f, const Polygon& t, const std::array<std::uint32_t, 3>& neighbours,
                                        const std::vector<char>& touched) {
  for (int k = 0; k < 3; ++k) {
    const std::uint32_t u = neighbours[k];
    if (u == kNoNeighbor || touched[u]) continue;
    for (const Plane& e : f.edges)
      if (e == t.edges[k]) return u;
  }
  return kNoNeighbor;
}

}  // namespace

std::optional<std::vector<std::uint32_t>> operand_ranges(const Soup& soup, std::size_t operands) {
  std::vector<std::uint32_t> begin(operands + 1, 0);
  for (std::size_t i = 1; i < soup.size(); ++i)
    if (soup[i].operand < soup[i - 1].operand) return std::nullopt;  // not grouped by operand
  for (std::size_t o = 0, i = 0; o <= operands; ++o) {
    while (i < soup.size() && soup[i].operand < o) ++i;
    begin[o] = static_cast<std::uint32_t>(i);
  }
  return begin;
}

std::optional<std::vector<OutputPolygon>> solve_solid(const Soup& soup, const GridTriangles& grid, const Box& box,
                                                      const SolveContext& ctx, const OperandTrees& trees) {
  const std::size_t n = soup.size(), operands = ctx.operands;
  // 1. Which triangles another operand's triangles meet, and which.
  const Partners partners = find_partners(grid, trees, n);
  std::vector<char> touched(n);
  for (std::uint32_t i = 0; i < n; ++i) touched[i] = partners.touched(i);
  const Tracer tracer{soup, trees, box, operands};
  std::atomic<bool> failed{false};

  // 2. Untouched triangles: components across manifold edges, one trace each.
  const Components comps = untouched_components(grid, touched);
  std::vector<int> comp_w(2 * operands * comps.roots.size());  // per component: front, then back
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, comps.roots.size(), 16), [&](const tbb::blocked_range<std::size_t>& r) {
    TraceScratch sc;
    Polygon t;
    Wnv front, back;
    for (std::size_t k = r.begin(); k != r.end() && !failed.load(); ++k) {
      const std::uint32_t id = comps.roots[k];
      const std::array<IntPoint, 3>& c = grid.corners[id];
      assign_triangle(c[0], c[1], c[2], t);
      if (!classify_from_outside(tracer, t, soup[id].operand, std::uint64_t{id} << 20, front, back, sc)) {
        failed = true;
        break;
      }
      std::copy(front.begin(), front.end(), comp_w.begin() + static_cast<std::ptrdiff_t>(2 * operands * k));
      std::copy(back.begin(), back.end(), comp_w.begin() + static_cast<std::ptrdiff_t>(2 * operands * k + operands));
    }
  });
  if (failed) return std::nullopt;
  const auto component_w = [&](std::uint32_t id, Wnv& front, Wnv& back) {
    const auto at = comp_w.begin() + static_cast<std::ptrdiff_t>(2 * operands * comps.index[id]);
    front.assign(at, at + static_cast<std::ptrdiff_t>(operands));
    back.assign(at + static_cast<std::ptrdiff_t>(operands), at + static_cast<std::ptrdiff_t>(2 * operands));
  };
  // Piece m of touched triangle t (input triangle id, operand o): across an
  // input edge to an untouched neighbour, else from the handover (when one is
  // given), else traced.
  const auto classify_piece = [&](const Polygon& f, const Polygon& t, std::uint32_t id, std::size_t m,
                                  std::uint32_t o, SolidHandover* handover, Wnv& front, Wnv& back,
                                  TraceScratch& sc) {
    const std::uint32_t via = untouched_neighbour_along(f, t, grid.neighbors[id], touched);
    if (via != kNoNeighbor) {
      component_w(via, front, back);
      front[o] = 0;
      back[o] = 1;
      return true;
    }
    if (handover && handover->find(f, front, back)) return true;
    return classify_from_outside(tracer, f, o, (std::uint64_t{id} << 20) ^ (m << 10), front, back, sc);
  };
  // Every piece of t at once, in parallel (no handover: it is sequential),
  // into w: per piece its front, then its back winding numbers.
  const auto classify_pieces = [&](const std::vector<Piece>& pieces, const Polygon& t, std::uint32_t id,
                                   std::uint32_t o, std::vector<int>& w) {
    w.resize(2 * operands * pieces.size());
    std::atomic<bool> ok{true};
    tbb::this_task_arena::isolate([&] {  // waiting here runs only these pieces, not other chunks
      tbb::parallel_for(tbb::blocked_range<std::size_t>(0, pieces.size(), 8), [&](const auto& r) {
        TraceScratch scratch;
        Wnv front, back;
        for (std::size_t m = r.begin(); m != r.end() && ok.load(std::memory_order_relaxed); ++m) {
          if (!classify_piece(pieces[m].poly, t, id, m, o, nullptr, front, back, scratch)) {
            ok = false;
            return;
          }
          const auto at = w.begin() + static_cast<std::ptrdiff_t>(2 * operands * m);
          std::copy(front.begin(), front.end(), at);
          std::copy(back.begin(), back.end(), at + static_cast<std::ptrdiff_t>(operands));
        }
      });
    });
    return ok.load();
  };
  const auto emitted = [&](const Wnv& front, const Wnv& back, bool& flip) {
    const bool in_front = ctx.inside(front), in_back = ctx.inside(back);
    flip = in_front;
    return in_front != in_back;
  };

  // 3. Touched triangles, in Morton order per operand (partners repeat from
  // one triangle to the next), in fixed chunks: each chunk's output is
  // ordered, so the result does not depend on the schedule. A piece with an
  // edge on an input edge whose other triangle is untouched takes that
  // triangle's winding numbers (solid_path.hpp, 4: nothing else comes near
  // that edge, so the same argument holds); the others are traced.
  constexpr std::size_t kChunk = 256;
  constexpr std::size_t kParallelPieces = 64;
  std::vector<std::pair<std::uint32_t, std::uint32_t>> chunks;  // (operand, first slot)
  for (std::uint32_t o = 0; o < operands; ++o)
    for (std::size_t s = 0; s < trees.tree[o].size(); s += kChunk) chunks.emplace_back(o, static_cast<std::uint32_t>(s));
  std::vector<std::vector<OutputPolygon>> chunk_out(chunks.size());
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, chunks.size(), 1), [&](const tbb::blocked_range<std::size_t>& r) {
    PolygonCache cache(grid);
    CutScratch cs;
    TraceScratch sc;
    SolidHandover handover(operands);
    Wnv front, back;
    std::vector<int> piece_w;  // per piece of a heavily cut triangle: front, then back
    for (std::size_t c = r.begin(); c != r.end(); ++c) {
      const auto [o, first] = chunks[c];
      handover.clear();  // a chunk's result must not depend on the chunks before it
      const TriangleTree& tree = trees.tree[o];
      std::vector<OutputPolygon>& out = chunk_out[c];
      for (std::size_t slot = first; slot < std::min(tree.size(), first + kChunk) && !failed.load(); ++slot) {
        const std::uint32_t id = trees.begin[o] + tree.item(slot);
        if (!touched[id]) continue;
        cs.partners = partners.of(id);
        cache.reset_if_full(cs.partners.size());
        const Polygon& t = cache.get(id);
        const bool whole = cut_triangle(t, id, cache, cs) && cs.pieces.size() == 1;
        handover.begin_triangle(id, t, cs.partners, grid);
        // A triangle cut into many pieces (a large face under a pile of
        // slivers: EMBER case 582 has three with 1,600-4,400) would hold one
        // thread for its traces: those are classified in parallel first, then
        // recorded in order. A piece's winding numbers are exact, whichever
        // way they are found, so the handover's state and the output are the
        // same as piece by piece.
        const bool parallel = cs.pieces.size() >= kParallelPieces;
        if (parallel && !classify_pieces(cs.pieces, t, id, o, piece_w)) {
          failed = true;
          break;
        }
        for (std::size_t m = 0; m < cs.pieces.size(); ++m) {
          const Polygon& f = cs.pieces[m].poly;
          if (parallel) {
            front.assign(piece_w.begin() + static_cast<std::ptrdiff_t>(2 * operands * m),
                         piece_w.begin() + static_cast<std::ptrdiff_t>(2 * operands * m + operands));
            back.assign(piece_w.begin() + static_cast<std::ptrdiff_t>(2 * operands * m + operands),
                        piece_w.begin() + static_cast<std::ptrdiff_t>(2 * operands * (m + 1)));
          } else if (!classify_piece(f, t, id, m, o, &handover, front, back, sc)) {
            failed = true;
            break;
          }
          handover.record(f, front, back);
          bool flip = false;
          if (emitted(front, back, flip)) out.push_back(output_of(soup[id], whole ? nullptr : &f, flip));
        }
      }
    }
  });
  if (failed) return std::nullopt;

  // 4. The output: untouched triangles by id, then the chunks in order.
  std::vector<char> keep(comps.roots.size());
  Wnv front, back;
  for (std::size_t k = 0; k < comps.roots.size(); ++k) {
    component_w(comps.roots[k], front, back);
    bool flip = false;
    keep[k] = emitted(front, back, flip) ? (flip ? 2 : 1) : 0;
  }
  // An untouched triangle whose neighbours are all untouched is settled
  // (OutputPolygon::settled): no other operand comes near it or them, and
  // its own operand meets it only in shared vertices and these edges.
  // Written in parallel at offsets counted per block of ids (a serial
  // push_back of every kept triangle was most of a large, lightly touched
  // Boolean's solve, and slower at 2 threads than at 1).
  const auto kept = [&](std::uint32_t i) { return !touched[i] && keep[comps.index[i]] != 0; };
  constexpr std::size_t kBlock = 4096;
  const std::size_t blocks = (n + kBlock - 1) / kBlock;
  std::vector<std::size_t> at(blocks + chunk_out.size() + 1, 0);  // blocks, then chunks
  tbb::parallel_for(std::size_t{0}, blocks, [&](std::size_t b) {
    for (std::size_t i = b * kBlock; i < std::min(n, (b + 1) * kBlock); ++i) at[b + 1] += kept(static_cast<std::uint32_t>(i));
  });
  for (std::size_t c = 0; c < chunk_out.size(); ++c) at[blocks + c + 1] = chunk_out[c].size();
  std::partial_sum(at.begin(), at.end(), at.begin());
  std::vector<OutputPolygon> out(at.back());
  tbb::parallel_for(std::size_t{0}, blocks, [&](std::size_t b) {
    std::size_t slot = at[b];
    for (std::size_t i = b * kBlock; i < std::min(n, (b + 1) * kBlock); ++i) {
      const auto id = static_cast<std::uint32_t>(i);
      if (!kept(id)) continue;
      OutputPolygon& o = out[slot++];
      o = output_of(soup[id], nullptr, keep[comps.index[id]] == 2);
      o.settled = std::none_of(grid.neighbors[id].begin(), grid.neighbors[id].end(),
                               [&](std::uint32_t j) { return j == kNoNeighbor || touched[j]; });
    }
  });
  tbb::parallel_for(std::size_t{0}, chunk_out.size(), [&](std::size_t c) {
    std::move(chunk_out[c].begin(), chunk_out[c].end(), out.begin() + static_cast<std::ptrdiff_t>(at[blocks + c]));
  });
  return out;
}

}  // namespace ember::core
