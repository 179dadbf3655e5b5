// Putting whole input triangles back together (whole_triangles.hpp).
#include "core/route/general/whole_triangles.hpp"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>

#include "core/support/sort_pairs.hpp"
#include "geometry/clip.hpp"

namespace ember::core {

namespace {

/// The shares are exact in double: each is 2^-s with s <= 52, and the pieces
/// of one triangle are distinct leaves of its split tree, so every partial
/// sum is a multiple of 2^-52 in [0, 1].
constexpr int kMaxExactSplits = 52;
static_assert(std::numeric_limits<double>::digits >= kMaxExactSplits + 1,
              "multiples of 2^-52 in [0, 1] must be exact doubles");

}  // namespace

std::size_t merge_whole_triangles(std::vector<OutputPolygon>& polys) {
  std::size_t n_ids = 0;
  for (const OutputPolygon& p : polys) n_ids = std::max<std::size_t>(n_ids, p.id + 1);
  if (polys.size() >= UINT32_MAX) return 0;  // positions are kept in 32 bits; nothing merged then
  std::vector<double> share(n_ids, 0.0);
  std::vector<std::uint32_t> first(n_ids, UINT32_MAX);
  std::vector<char> mixed(n_ids, 0);
  // One serial pass in output order (a few operations per polygon).
  for (std::size_t i = 0; i < polys.size(); ++i) {
    const OutputPolygon& p = polys[i];
    if (first[p.id] == UINT32_MAX) {
      first[p.id] = static_cast<std::uint32_t>(i);
    } else if (const OutputPolygon& q = polys[first[p.id]];
               q.flip != p.flip || q.layer_lo != p.layer_lo || q.layer_hi != p.layer_hi) {
      mixed[p.id] = 1;
    }
    if (!p.whole_piece || p.splits > kMaxExactSplits) {
      mixed[p.id] = 1;
    } else {
      share[p.id] += std::ldexp(1.0, -p.splits);
    }
  }
  // Decided before any polygon changes (a merged triangle's first piece is rewritten below).
  std::vector<char> merged(n_ids, 0);
  std::size_t count = 0;
  for (std::size_t id = 0; id < n_ids; ++id) {
    merged[id] = first[id] != UINT32_MAX && !mixed[id] && share[id] == 1.0 && polys[first[id]].splits > 0;
    count += merged[id];
  }
  // The first piece of each merged triangle becomes the triangle; the others go.
  std::vector<char> drop(polys.size(), 0);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, polys.size(), 1024), [&](const auto& r) {
    for (std::size_t i = r.begin(); i != r.end(); ++i) {
      OutputPolygon& p = polys[i];
      if (!merged[p.id]) continue;
      if (first[p.id] != i) {
        drop[i] = 1;
        continue;
      }
      // Unbuilt, as the soup held it.
      p.vertices = {};
      p.path = OutputPolygon::kNoPath;
      p.splits = 0;
    }
  });
  std::size_t kept = 0;
  for (std::size_t i = 0; i < polys.size(); ++i) {
    if (drop[i]) continue;
    if (kept != i) polys[kept] = std::move(polys[i]);
    ++kept;
  }
  polys.resize(kept);
  return count;
}

void expand_path_pieces(std::vector<OutputPolygon>& polys, std::span<const SplitPath> paths) {
  // Grouped by triangle: the pieces of one triangle share the cuts near the
  // root of their paths, which are then made once per triangle (as the
  // subdivision made them), not once per piece.
  std::vector<std::pair<std::uint32_t, std::uint32_t>> order;  // (triangle id, position)
  for (std::size_t i = 0; i < polys.size(); ++i)
    if (polys[i].path != OutputPolygon::kNoPath) order.emplace_back(polys[i].id, static_cast<std::uint32_t>(i));
  if (order.empty()) return;
  sort_pairs(order);
  std::vector<std::size_t> group_begin;
  for (std::size_t k = 0; k < order.size(); ++k)
    if (k == 0 || order[k].first != order[k - 1].first) group_begin.push_back(k);
  group_begin.push_back(order.size());
  struct Cut {
    const SplitStep* at;  ///< the piece in the box of this step (null: the whole triangle)
    SoupPolygon piece;
  };
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, group_begin.size() - 1, 64), [&](const auto& r) {
    std::vector<Cut> cuts;  // per triangle, each piece that a cut made on the way
    std::vector<const SplitStep*> steps;
    SoupPolygon piece;
    Polygon neg, pos;
    for (std::size_t g = r.begin(); g != r.end(); ++g) {
      cuts.clear();
      for (std::size_t k = group_begin[g]; k < group_begin[g + 1]; ++k) {
        OutputPolygon& p = polys[order[k].second];
        if (cuts.empty()) {
          cuts.push_back({nullptr, unbuilt_triangle(*p.corners, p.id, p.operand)});
          materialize(cuts.back().piece);
        }
        // Up the path to the deepest step whose piece is known, then down.
        steps.clear();
        const SplitStep* s = paths[p.path].get();
        const Cut* from = nullptr;
        for (;; s = s->parent.get()) {
          for (const Cut& c : cuts)
            if (c.at == s) from = &c;
          if (from) break;
          steps.push_back(s);
        }
        piece.poly = std::make_unique<Polygon>(*from->piece.poly);
        piece.lo = from->piece.lo;
        piece.hi = from->piece.hi;
        for (auto it = steps.rbegin(); it != steps.rend(); ++it) {
          const SplitStep& step = **it;
          // As split_range: a piece whose conservative box lies on one side is
          // not clipped (it lies on the path's side, or it would not be here).
          const auto at = static_cast<double>(step.position);
          if (piece.hi[step.axis] < at || piece.lo[step.axis] > at) continue;
          if (clip(*piece.poly, axis_plane(step.axis, step.position), neg, pos) != ClipSide::Both) continue;
          std::swap(*piece.poly, step.upper ? pos : neg);
          update_bounds(piece);
          cuts.push_back(
              {&step, SoupPolygon{std::make_unique<Polygon>(*piece.poly), 0, 0, piece.lo, piece.hi, 0, nullptr}});
        }
        p.vertices.assign(piece.poly->vertices.begin(), piece.poly->vertices.end());
        p.path = OutputPolygon::kNoPath;
      }
    }
  });
}

}  // namespace ember::core
