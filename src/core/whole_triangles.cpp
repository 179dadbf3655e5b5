// Putting whole input triangles back together (whole_triangles.hpp).
#include "core/whole_triangles.hpp"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>

#include "ember/geometry/clip.hpp"

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
    } else if (polys[first[p.id]].flip != p.flip) {
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
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, polys.size(), 256), [&](const auto& r) {
    std::vector<const SplitStep*> steps;
    SoupPolygon piece;
    Polygon neg, pos;
    for (std::size_t i = r.begin(); i != r.end(); ++i) {
      OutputPolygon& p = polys[i];
      if (p.path == OutputPolygon::kNoPath) continue;
      steps.clear();
      for (const SplitStep* s = paths[p.path].get(); s; s = s->parent.get()) steps.push_back(s);
      piece = unbuilt_triangle(*p.corners, p.id, p.operand);
      materialize(piece);
      for (auto it = steps.rbegin(); it != steps.rend(); ++it) {
        const SplitStep& s = **it;
        // As split_range: a piece whose conservative box lies on one side is
        // not clipped (it lies on the path's side, or it would not be here).
        const auto at = static_cast<double>(s.position);
        if (piece.hi[s.axis] < at || piece.lo[s.axis] > at) continue;
        if (clip(*piece.poly, axis_plane(s.axis, s.position), neg, pos) != ClipSide::Both) continue;
        std::swap(*piece.poly, s.upper ? pos : neg);
        update_bounds(piece);
      }
      p.vertices.assign(piece.poly->vertices.begin(), piece.poly->vertices.end());
      p.path = OutputPolygon::kNoPath;
    }
  });
}

}  // namespace ember::core
