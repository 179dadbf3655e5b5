#pragma once
// Order-keeping parallel selection: the entries made from the indices of
// [0, n) that pass a test, in increasing index order.
//
// A serial push_back over every triangle or vertex of a large input is a
// stretch in which one thread works and the others wait, and several such
// passes add up to a noticeable part of a Boolean that otherwise runs on
// every thread. Here both passes run over fixed blocks (count, then
// write at the block's offset), so the result does not depend on the
// schedule, and the output's pages are first touched in parallel
// (FillVector).
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <numeric>
#include <vector>

#include "core/support/fill_vector.hpp"

namespace ember::core {

/// Indices per block of parallel_select (its tests straddle the boundaries).
inline constexpr std::size_t kSelectBlock = 4096;

/// make(i) for every i in [0, n) with keep(i), in order of i. keep is
/// called twice per index and must give the same answer both times; make
/// is called once per kept index and never for another. Both are called
/// from several threads at once, for different indices.
template <typename T, typename Keep, typename Make>
FillVector<T> parallel_select(std::size_t n, const Keep& keep, const Make& make) {
  constexpr std::size_t kBlock = kSelectBlock;
  const std::size_t blocks = (n + kBlock - 1) / kBlock;
  std::vector<std::size_t> at(blocks + 1, 0);
  tbb::parallel_for(std::size_t{0}, blocks, [&](std::size_t b) {
    std::size_t count = 0;
    for (std::size_t i = b * kBlock, end = std::min(n, i + kBlock); i < end; ++i) count += keep(i) ? 1 : 0;
    at[b + 1] = count;
  });
  std::partial_sum(at.begin(), at.end(), at.begin());
  FillVector<T> out(at.back());  // every slot written below
  tbb::parallel_for(std::size_t{0}, blocks, [&](std::size_t b) {
    std::size_t slot = at[b];
    for (std::size_t i = b * kBlock, end = std::min(n, i + kBlock); i < end; ++i)
      if (keep(i)) out[slot++] = make(i);
  });
  return out;
}

/// The indices i in [0, n) with keep(i), ascending (n < 2^32).
template <typename Keep>
FillVector<std::uint32_t> parallel_indices_where(std::size_t n, const Keep& keep) {
  return parallel_select<std::uint32_t>(n, keep, [](std::size_t i) { return static_cast<std::uint32_t>(i); });
}

/// n copies of `value`, written in parallel (std::vector's own fill is one
/// serial pass that also takes every page fault of the fresh memory).
template <typename T>
FillVector<T> parallel_filled(std::size_t n, const T& value) {
  FillVector<T> out(n);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, 16384), [&](const tbb::blocked_range<std::size_t>& r) {
    std::fill(out.begin() + static_cast<std::ptrdiff_t>(r.begin()), out.begin() + static_cast<std::ptrdiff_t>(r.end()),
              value);
  });
  return out;
}

}  // namespace ember::core
