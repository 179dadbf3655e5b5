#pragma once
// Sorting (key, index) pairs: the mesh stage groups corners by edge, the
// proof orders triangles along a Hilbert curve, the vertex index buckets
// positions, ... all by sorting an array of (integer key, 32-bit index)
// pairs that was filled in index order. A comparison sort spends ~17
// compare-and-move steps per element on 10^5 elements (6-9% of a typical
// Boolean's instructions went into them); a stable LSD radix sort on the
// bits in which the keys differ takes 3-6 passes of a few instructions each.
#include <cstdint>
#include <utility>
#include <vector>

#include "core/fill_vector.hpp"

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

}  // namespace ember::core
