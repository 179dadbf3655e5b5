#pragma once
// Edge matching on welded vertex ids (closedness, manifold components). The
// ids come from the set-up's weld of the grid vertices (grid_input.hpp).
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "core/fill_vector.hpp"
#include "ember/geometry/plane.hpp"

namespace ember::core {

struct WeldedTriangles {
  std::span<const std::array<std::uint32_t, 3>> ids;  ///< per triangle, its corners' vertex ids
  std::size_t vertex_count = 0;
};

/// One use of an undirected edge {lo, hi} by a triangle's directed edge.
struct EdgeUse {
  std::uint32_t hi;   ///< the edge's higher vertex id
  std::uint32_t tri;  ///< the triangle using it
  bool forward;       ///< the triangle runs lo -> hi
  std::uint8_t edge;  ///< which edge of the triangle: corner edge -> edge + 1
  friend bool operator<(const EdgeUse& x, const EdgeUse& y) { return x.hi != y.hi ? x.hi < y.hi : x.tri < y.tri; }
};

/// Calls f(uses) once per undirected edge with the span of its uses, ordered
/// by triangle. Edges of collapsed corners (equal ids) are skipped. Linear:
/// a counting sort by the lower id, then tiny per-vertex sorts, in parallel
/// over the vertices: f runs concurrently for different edges (it must be
/// thread-safe; the uses it sees do not depend on the schedule).
template <typename F>
void for_each_edge(const WeldedTriangles& welded, F&& f) {
  std::vector<std::uint32_t> start(welded.vertex_count + 1, 0);
  for (const auto& v : welded.ids)
    for (int e = 0; e < 3; ++e)
      if (v[e] != v[(e + 1) % 3]) ++start[std::min(v[e], v[(e + 1) % 3]) + 1];
  for (std::size_t i = 1; i < start.size(); ++i) start[i] += start[i - 1];
  FillVector<EdgeUse> uses(start.back());  // every slot written by the fill below
  std::vector<std::uint32_t> fill(start.begin(), start.end() - 1);
  for (std::uint32_t t = 0; t < welded.ids.size(); ++t)
    for (int e = 0; e < 3; ++e) {
      const std::uint32_t a = welded.ids[t][e], b = welded.ids[t][(e + 1) % 3];
      if (a != b) uses[fill[std::min(a, b)]++] = {std::max(a, b), t, a < b, static_cast<std::uint8_t>(e)};
    }
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, start.size() - 1, 4096), [&](const tbb::blocked_range<std::size_t>& r) {
    for (std::size_t v = r.begin(); v != r.end(); ++v) {
      const auto first = uses.begin() + start[v], last = uses.begin() + start[v + 1];
      std::sort(first, last);
      for (auto it = first; it != last;) {
        auto jt = it;
        while (jt != last && jt->hi == it->hi) ++jt;
        f(std::span<const EdgeUse>(&*it, static_cast<std::size_t>(jt - it)));
        it = jt;
      }
    }
  });
}

}  // namespace ember::core
