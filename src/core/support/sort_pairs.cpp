#include "core/support/sort_pairs.hpp"

#include <tbb/parallel_for.h>
#include <tbb/parallel_sort.h>

#include <algorithm>
#include <array>
#include <bit>
#include <limits>

namespace ember::core {

namespace {

// 11-bit digits: 2,048 counters of 8 bytes per chunk stay in L1 during the
// count, and a 34-bit key (an edge of 2^17 vertices) needs 4 passes. Below
// kWideDigitsFrom pairs the 2,048 counters (filled and summed per pass) cost
// more than the pairs: 8-bit digits, 256 counters. kWideDigitsFrom lies
// where, on random 32-bit and edge keys, the wider digits' fewer passes
// begin to outweigh their larger counter arrays.
constexpr int kWideDigitBits = 11, kNarrowDigitBits = 8;
constexpr std::size_t kWideDigitsFrom = 4096;
constexpr std::size_t kMaxBuckets = std::size_t{1} << kWideDigitBits;
// Fixed chunks (not the scheduler's ranges): the scatter offsets, and hence
// the result, are the same for any thread count.
constexpr std::size_t kChunk = std::size_t{1} << 16;
// Below this a comparison sort is as fast and needs no second buffer. (Not
// much above it: on random pairs the comparisons defeat the branch
// predictor, and the radix sort is several times faster.)
constexpr std::size_t kSmall = 64;

template <typename Key, typename Alloc>
using Pairs = std::vector<std::pair<Key, std::uint32_t>, Alloc>;

/// The key bits in which some two keys differ; `values_ordered` says
/// whether the values are non-decreasing (the fast path's condition). One
/// parallel pass over the same fixed chunks as the sort (a serial scan of
/// millions of pairs would be the sort's only serial part).
template <typename Key, typename Alloc>
Key varying_bits(const Pairs<Key, Alloc>& v, bool& values_ordered) {
  struct Chunk {
    Key any = 0, all = std::numeric_limits<Key>::max();
    bool ordered = true;
  };
  const std::size_t n = v.size(), chunks = (n + kChunk - 1) / kChunk;
  std::vector<Chunk> part(chunks);
  tbb::parallel_for(std::size_t{0}, chunks, [&](std::size_t c) {
    Chunk& p = part[c];
    for (std::size_t i = c * kChunk, e = std::min(n, i + kChunk); i < e; ++i) {
      p.any |= v[i].first;
      p.all &= v[i].first;
      p.ordered &= i == c * kChunk || v[i - 1].second <= v[i].second;
    }
  });
  Key any = 0, all = std::numeric_limits<Key>::max();
  values_ordered = true;
  for (std::size_t c = 0; c < chunks; ++c) {
    any |= part[c].any;
    all &= part[c].all;
    values_ordered &= part[c].ordered && (c == 0 || v[c * kChunk - 1].second <= v[c * kChunk].second);
  }
  return any ^ all;
}

/// First bit at or above `from` in which keys differ, or the key width.
template <typename Key>
int next_varying(Key varying, int from) {
  constexpr int kBits = std::numeric_limits<Key>::digits;
  if (from >= kBits) return kBits;
  const Key rest = varying >> from;
  return rest == 0 ? kBits : from + std::countr_zero(rest);
}

/// Stable LSD radix sort by key, over the windows of digit bits that start
/// at a varying bit (bits that no key differs in would only copy).
template <typename Key, typename Alloc>
void radix_sort_by_key(Pairs<Key, Alloc>& v, Key varying) {
  constexpr int kBits = std::numeric_limits<Key>::digits;
  const std::size_t n = v.size(), chunks = (n + kChunk - 1) / kChunk;
  const int digit_bits = n < kWideDigitsFrom ? kNarrowDigitBits : kWideDigitBits;
  const std::size_t buckets = std::size_t{1} << digit_bits;
  // The caller's vector type, so that the result can be swapped in; a
  // FillVector's buffer is not zeroed first (each pass writes every slot).
  Pairs<Key, Alloc> buffer(n);
  std::vector<std::array<std::size_t, kMaxBuckets>> at(chunks);
  auto* src = &v;
  auto* dst = &buffer;
  for (int shift = next_varying(varying, 0); shift < kBits; shift = next_varying(varying, shift + digit_bits)) {
    const std::size_t mask = buckets - 1;
    const auto digit = [shift, mask](Key k) { return static_cast<std::size_t>(k >> shift) & mask; };
    tbb::parallel_for(std::size_t{0}, chunks, [&](std::size_t c) {
      std::fill_n(at[c].begin(), buckets, 0);
      for (std::size_t i = c * kChunk, e = std::min(n, i + kChunk); i < e; ++i) ++at[c][digit((*src)[i].first)];
    });
    // Exclusive prefix in (digit, chunk) order: chunk c's items of digit d
    // follow those of earlier chunks, which keeps the sort stable.
    std::size_t sum = 0;
    for (std::size_t d = 0; d < buckets; ++d)
      for (std::size_t c = 0; c < chunks; ++c) sum += std::exchange(at[c][d], sum);
    tbb::parallel_for(std::size_t{0}, chunks, [&](std::size_t c) {
      for (std::size_t i = c * kChunk, e = std::min(n, i + kChunk); i < e; ++i)
        (*dst)[at[c][digit((*src)[i].first)]++] = (*src)[i];
    });
    std::swap(src, dst);
  }
  if (src != &v) v.swap(buffer);
}

template <typename Key, typename Alloc>
void sort_pairs_impl(Pairs<Key, Alloc>& v) {
  if (v.size() < kSmall) {
    std::sort(v.begin(), v.end());
    return;
  }
  bool values_ordered = false;
  const Key varying = varying_bits(v, values_ordered);
  // Stable by key with non-decreasing values is exactly pair order.
  if (values_ordered) {
    radix_sort_by_key(v, varying);
  } else {
    tbb::parallel_sort(v.begin(), v.end());
  }
}

}  // namespace

template <typename Key, typename Alloc>
void sort_pairs(std::vector<std::pair<Key, std::uint32_t>, Alloc>& v) {
  sort_pairs_impl(v);
}

template void sort_pairs(std::vector<std::pair<std::uint64_t, std::uint32_t>>&);
template void sort_pairs(std::vector<std::pair<std::uint32_t, std::uint32_t>>&);
template void sort_pairs(FillVector<std::pair<std::uint64_t, std::uint32_t>>&);
template void sort_pairs(FillVector<std::pair<std::uint32_t, std::uint32_t>>&);

}  // namespace ember::core
