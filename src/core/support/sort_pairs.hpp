#pragma once
// Sorting (key, index) pairs: the mesh stage groups corners by edge, the
// proof orders triangles along a Hilbert curve, the vertex index buckets
// positions, ... all by sorting an array of (integer key, 32-bit index)
// pairs that was filled in index order. A comparison sort spends ~log2(n)
// compare-and-move steps per element (~17 on 10^5 elements), and these
// sorts run in several stages of every Boolean; a stable LSD radix sort on
// the bits in which the keys differ takes 3-6 passes of a few instructions
// each.
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_sort.h>

#include <algorithm>
#include <cstdint>
#include <utility>
#include <vector>

#include "core/support/fill_vector.hpp"

namespace ember::core {

/// Sorts v ascending in the order of std::pair (key first, then value), the
/// same result as std::sort for any input. Fast path: when the values are
/// non-decreasing in v's order (an array filled in index order), a stable
/// radix sort by key alone gives that order; otherwise it falls back to a
/// comparison sort. Parallel over fixed chunks, so the result never depends
/// on the thread count (it is unique anyway).
/// For std::vector and FillVector (fill_vector.hpp), keys of 32 or 64 bits.
template <typename Key, typename Alloc>
void sort_pairs(std::vector<std::pair<Key, std::uint32_t>, Alloc>& v);

/// After sort_pairs by a leading part of an order: sorts each run of equal
/// keys in v by `before`, a strict total order on its pairs (ties broken by
/// the value), which completes the order. Runs are mostly short when the key
/// is most of it (the grid weld's x of (x, y, z); the crossing names' edge of
/// (edge, face)): one radix sort by the key and these small sorts cost far
/// less than radix passes over the whole order. Each run is sorted by the
/// block its first pair falls in (it may reach past the block), long runs
/// in parallel; the order being total, the result is unique. A run is
/// sorted in a copy and only its values are written back: the keys, which
/// the next block's owner reads to find its runs, are never written.
template <typename Pairs, typename Before>
void sort_equal_key_runs(Pairs& v, Before before) {
  using Pair = std::pair<typename Pairs::value_type::first_type, std::uint32_t>;
  constexpr std::size_t kLongRun = 4096;
  const std::size_t n = v.size();
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, 4096), [&](const tbb::blocked_range<std::size_t>& r) {
    std::vector<Pair> run;
    for (std::size_t i = r.begin(); i != r.end(); ++i) {
      if (i > 0 && v[i - 1].first == v[i].first) continue;  // not a run's first pair
      std::size_t end = i + 1;
      while (end < n && v[end].first == v[i].first) ++end;
      if (end - i < 2) continue;
      run.assign(v.begin() + static_cast<std::ptrdiff_t>(i), v.begin() + static_cast<std::ptrdiff_t>(end));
      if (run.size() >= kLongRun) {
        tbb::parallel_sort(run.begin(), run.end(), before);
      } else {
        std::sort(run.begin(), run.end(), before);
      }
      for (std::size_t k = 0; k < run.size(); ++k) v[i + k].second = run[k].second;
    }
  });
}

}  // namespace ember::core
