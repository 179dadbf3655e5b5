// The solid path's polygon-local BSPs (solid_cuts.hpp).
#include "core/route/solid/solid_cuts.hpp"

#include <tbb/blocked_range.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <algorithm>

namespace ember::core {

namespace {

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

/// Below this many pieces a partner's cut runs piece by piece.
constexpr std::size_t kParallelCut = 256;

/// The transverse cut of cut_triangle by partner o over pieces 0 .. n - 1 at
/// once: the pieces that o's plane splits are split in parallel, then the
/// halves are put in place in piece order, as the serial loop does (each
/// piece is cut by o on its own, and the new halves are not cut by o again).
/// For a large face under a pile of slivers (thousands of partners and of
/// pieces), whose cuts would otherwise hold one thread.
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

}  // namespace

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
  cs.coplanar.assign(cs.partners.size(), 0);
  for (std::size_t k = 0; k < cs.partners.size(); ++k) {
    const std::uint32_t q = cs.partners[k];
    const Polygon& o = cache.get(q);
    cs.coplanar[k] = coplanar(t.support, o.support) ? 1 : 0;
    if (cs.coplanar[k] || !touches_plane(cache.corners(q), t.support, cs.other_signs)) continue;
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

}  // namespace ember::core
