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

#include "core/support/fill_vector.hpp"
#include "geometry/plane.hpp"

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

/// Sorts one vertex's uses into EdgeUse order. They arrive ordered by
/// (triangle, edge): every pass of for_each_edge keeps the order of the one
/// before, and the triangles are read in order. So a stable sort by hi alone
/// gives the total order: an insertion sort for the few uses of an ordinary
/// vertex (a comparison sort's three-key compares were most of the matching's
/// per-vertex work), the comparison sort for a fan's centre.
template <typename It>
void sort_by_hi(It first, It last) {
  if (last - first > 16) {
    std::sort(first, last);
    return;
  }
  for (It it = first + (first != last); it < last; ++it) {
    const EdgeUse x = *it;
    It at = it;
    for (; at != first && (at - 1)->hi > x.hi; --at) *at = *(at - 1);
    *at = x;
  }
}

/// Calls f(uses) once per undirected edge with the span of its uses, ordered
/// by triangle. Edges of collapsed corners (equal ids) are skipped. Linear: a
/// two-level counting sort by the lower id, then tiny per-vertex sorts, every
/// pass parallel over fixed blocks (a serial counting sort would dominate
/// the edge matching at any thread count; atomic counters instead cost more
/// than they save at few threads):
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
  // Triangles per block: at least 16384, and at most 256 blocks, so the
  // table of blocks x buckets stays linear in the input. Lower ids per bucket:
  // 4096 (a bucket's counters fit in L1).
  constexpr std::size_t kBucket = 4096, kMaxBlocks = 256;
  const std::size_t n = welded.ids.size();
  const std::size_t block_size = std::max<std::size_t>(16384, (n + kMaxBlocks - 1) / kMaxBlocks);
  const std::size_t blocks = (n + block_size - 1) / block_size;
  const std::size_t buckets = std::max<std::size_t>(1, (welded.vertex_count + kBucket - 1) / kBucket);
  const auto for_each_use = [&](std::size_t block, auto&& use) {
    for (std::size_t t = block * block_size, end = std::min(n, t + block_size); t < end; ++t)
      for (int e = 0; e < 3; ++e) {
        const std::uint32_t a = welded.ids[t][e], b = welded.ids[t][(e + 1) % 3];
        if (a != b)
          use(Use{std::min(a, b),
                  {std::max(a, b), static_cast<std::uint32_t>(t), a < b, static_cast<std::uint8_t>(e)}});
      }
  };
  // slot[bucket * blocks + block]: first the counts, then where the block
  // starts writing (bucket-major, so the offsets are one pass in memory order).
  // Each block counts and writes through cursors of its own (no cache line
  // shared with another block's in the hot loops).
  std::vector<std::size_t> slot(buckets * blocks, 0);
  tbb::parallel_for(std::size_t{0}, blocks, [&](std::size_t k) {
    std::vector<std::size_t> count(buckets, 0);
    for_each_use(k, [&](const Use& u) { ++count[u.lo / kBucket]; });
    for (std::size_t b = 0; b < buckets; ++b) slot[b * blocks + k] = count[b];
  });
  std::vector<std::size_t> bucket_begin(buckets + 1, 0);
  std::size_t sum = 0;
  for (std::size_t i = 0; i < slot.size(); ++i) {
    if (i % blocks == 0) bucket_begin[i / blocks] = sum;
    const std::size_t count = slot[i];
    slot[i] = sum;
    sum += count;
  }
  bucket_begin[buckets] = sum;
  FillVector<Use> uses(sum);  // every slot written below
  tbb::parallel_for(std::size_t{0}, blocks, [&](std::size_t k) {
    std::vector<std::size_t> at(buckets);
    for (std::size_t b = 0; b < buckets; ++b) at[b] = slot[b * blocks + k];
    for_each_use(k, [&](const Use& u) { uses[at[u.lo / kBucket]++] = u; });
  });
  tbb::parallel_for(std::size_t{0}, buckets, [&](std::size_t b) {
    const std::size_t first_id = b * kBucket, begin = bucket_begin[b], end = bucket_begin[b + 1];
    if (begin == end) return;
    std::vector<std::uint32_t> start(kBucket + 1, 0);
    for (std::size_t i = begin; i < end; ++i) ++start[uses[i].lo - first_id + 1];
    for (std::size_t v = 1; v <= kBucket; ++v) start[v] += start[v - 1];
    std::vector<EdgeUse> sorted(end - begin);
    std::vector<std::uint32_t> fill(start.begin(), start.end() - 1);
    for (std::size_t i = begin; i < end; ++i) sorted[fill[uses[i].lo - first_id]++] = uses[i].use;
    for (std::size_t v = 0; v < kBucket; ++v) {
      const auto first = sorted.begin() + start[v], last = sorted.begin() + start[v + 1];
      sort_by_hi(first, last);
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
