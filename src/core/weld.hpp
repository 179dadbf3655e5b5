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
  /// A total order (a triangle with a repeated corner uses one edge twice),
  /// so the sorted uses do not depend on the order the parallel fill left.
  friend bool operator<(const EdgeUse& x, const EdgeUse& y) {
    if (x.hi != y.hi) return x.hi < y.hi;
    return x.tri != y.tri ? x.tri < y.tri : x.edge < y.edge;
  }
};

/// Calls f(uses) once per undirected edge with the span of its uses, ordered
/// by triangle. Edges of collapsed corners (equal ids) are skipped. Linear: a
/// two-level counting sort by the lower id, then tiny per-vertex sorts, every
/// pass parallel over fixed blocks (a serial counting sort was half of the
/// 1.08M-triangle union's edge matching, and all of it at 16 threads; atomic
/// counters instead cost more than they saved at 2 threads):
///  1. each block of triangles counts its uses per bucket of kBucket lower ids;
///  2. each block writes its uses into its own slots of each bucket (bucket
///     by bucket, blocks in order: the result does not depend on the schedule);
///  3. each bucket sorts its uses by lower id into a buffer of its own and
///     hands them to f vertex by vertex.
/// f runs concurrently for different edges (it must be thread-safe; the uses
/// it sees and their order do not depend on the schedule).
template <typename F>
void for_each_edge(const WeldedTriangles& welded, F&& f) {
  struct Use {
    std::uint32_t lo;
    EdgeUse use;
  };
  constexpr std::size_t kBlock = 16384, kBucket = 4096;  // triangles per block, lower ids per bucket
  const std::size_t n = welded.ids.size();
  const std::size_t blocks = (n + kBlock - 1) / kBlock, buckets = welded.vertex_count / kBucket + 1;
  const auto for_each_use = [&](std::size_t block, auto&& use) {
    for (std::size_t t = block * kBlock, end = std::min(n, t + kBlock); t < end; ++t)
      for (int e = 0; e < 3; ++e) {
        const std::uint32_t a = welded.ids[t][e], b = welded.ids[t][(e + 1) % 3];
        if (a != b) use(Use{std::min(a, b), {std::max(a, b), static_cast<std::uint32_t>(t), a < b, static_cast<std::uint8_t>(e)}});
      }
  };
  // slot[block * buckets + bucket]: first the counts, then where the block writes.
  std::vector<std::size_t> slot(blocks * buckets, 0);
  tbb::parallel_for(std::size_t{0}, blocks, [&](std::size_t k) {
    for_each_use(k, [&](const Use& u) { ++slot[k * buckets + u.lo / kBucket]; });
  });
  std::vector<std::size_t> bucket_begin(buckets + 1, 0);
  for (std::size_t b = 0, sum = 0; b < buckets; ++b) {
    bucket_begin[b] = sum;
    for (std::size_t k = 0; k < blocks; ++k) {
      const std::size_t count = slot[k * buckets + b];
      slot[k * buckets + b] = sum;
      sum += count;
    }
    bucket_begin[b + 1] = sum;
  }
  FillVector<Use> uses(bucket_begin.back());  // every slot written below
  tbb::parallel_for(std::size_t{0}, blocks, [&](std::size_t k) {
    for_each_use(k, [&](const Use& u) { uses[slot[k * buckets + u.lo / kBucket]++] = u; });
  });
  tbb::parallel_for(std::size_t{0}, buckets, [&](std::size_t b) {
    const std::size_t first_id = b * kBucket, begin = bucket_begin[b], end = bucket_begin[b + 1];
    std::vector<std::uint32_t> start(kBucket + 1, 0);
    for (std::size_t i = begin; i < end; ++i) ++start[uses[i].lo - first_id + 1];
    for (std::size_t v = 1; v <= kBucket; ++v) start[v] += start[v - 1];
    std::vector<EdgeUse> sorted(end - begin);
    std::vector<std::uint32_t> fill(start.begin(), start.end() - 1);
    for (std::size_t i = begin; i < end; ++i) sorted[fill[uses[i].lo - first_id]++] = uses[i].use;
    for (std::size_t v = 0; v < kBucket; ++v) {
      const auto first = sorted.begin() + start[v], last = sorted.begin() + start[v + 1];
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
