// sort_pairs (src/core/sort_pairs.hpp) must give std::sort's order for any
// input: the radix fast path (values non-decreasing) and the fallback alike,
// at any thread count, across chunk boundaries and for keys whose varying
// bits are sparse (the radix windows skip the bits no key differs in).
// sort_equal_key_runs completes a key order to a total one, run by run.
#include <gtest/gtest.h>

#include <tbb/task_arena.h>

#include <algorithm>
#include <random>

#include "core/support/sort_pairs.hpp"

namespace ember::test {
namespace {

template <typename Key>
using Pairs = std::vector<std::pair<Key, std::uint32_t>>;

/// n pairs with keys drawn from `key`, values 0, 1, 2, ... (the fast path's
/// input) or, with `shuffled_values`, a random permutation of them.
template <typename Key, typename Gen>
Pairs<Key> make_pairs(std::size_t n, Gen&& key, bool shuffled_values, std::mt19937_64& rng) {
  Pairs<Key> v(n);
  for (std::size_t i = 0; i < n; ++i) v[i] = {key(), static_cast<std::uint32_t>(i)};
  if (shuffled_values) {
    std::vector<std::uint32_t> vals(n);
    for (std::size_t i = 0; i < n; ++i) vals[i] = static_cast<std::uint32_t>(i / 3);  // repeats too
    std::shuffle(vals.begin(), vals.end(), rng);
    for (std::size_t i = 0; i < n; ++i) v[i].second = vals[i];
  }
  return v;
}

template <typename Key>
void expect_sorted_like_std(Pairs<Key> v, int threads) {
  Pairs<Key> expected = v;
  std::sort(expected.begin(), expected.end());
  tbb::task_arena(threads).execute([&] { core::sort_pairs(v); });
  ASSERT_EQ(v.size(), expected.size());
  EXPECT_TRUE(v == expected) << "n = " << v.size() << ", threads = " << threads;
}

TEST(SortPairs, MatchesStdSortOn64BitKeys) {
  std::mt19937_64 rng(7);
  // Sizes below the comparison-sort threshold, 8-bit digits (up to 4,095
  // pairs), 11-bit digits in one chunk and in several chunks with a ragged
  // last one.
  for (const std::size_t n : {std::size_t{0}, std::size_t{1}, std::size_t{50}, std::size_t{100}, std::size_t{700},
                              std::size_t{4095}, std::size_t{5000}, std::size_t{65536}, std::size_t{3 * 65536 + 17}}) {
    for (const bool shuffled : {false, true}) {
      // Full-width keys; edge-like keys (min << 32 | max over 2^17 ids: bits
      // 17..31 never vary); few distinct keys (many ties broken by value);
      // keys that differ only in the top bit.
      std::uniform_int_distribution<std::uint64_t> any;
      std::uniform_int_distribution<std::uint64_t> id(0, (1u << 17) - 1);
      std::uniform_int_distribution<std::uint64_t> few(0, 6);
      const std::vector<Pairs<std::uint64_t>> inputs = {
          make_pairs<std::uint64_t>(
              n, [&] { return any(rng); }, shuffled, rng),
          make_pairs<std::uint64_t>(
              n,
              [&] {
                const std::uint64_t a = id(rng), b = id(rng);
                return (std::min(a, b) << 32) | std::max(a, b);
              },
              shuffled, rng),
          make_pairs<std::uint64_t>(
              n, [&] { return few(rng) * 0x0101010101ull; }, shuffled, rng),
          make_pairs<std::uint64_t>(
              n, [&] { return (few(rng) & 1) << 63; }, shuffled, rng),
      };
      for (const auto& v : inputs)
        for (const int threads : {1, 3}) expect_sorted_like_std(v, threads);
    }
  }
}

TEST(SortPairs, MatchesStdSortOn32BitKeys) {
  std::mt19937_64 rng(11);
  std::uniform_int_distribution<std::uint32_t> any;
  std::uniform_int_distribution<std::uint32_t> small(0, 999);
  for (const std::size_t n : {std::size_t{3000}, std::size_t{2 * 65536 + 5}}) {
    for (const bool shuffled : {false, true}) {
      expect_sorted_like_std(make_pairs<std::uint32_t>(
                                 n, [&] { return any(rng); }, shuffled, rng),
                             2);
      expect_sorted_like_std(make_pairs<std::uint32_t>(
                                 n, [&] { return small(rng); }, shuffled, rng),
                             2);
    }
  }
}

// The FillVector instantiation (unzeroed radix buffer, fill_vector.hpp) gives
// the same order as the std::vector one, odd and even pass counts alike.
TEST(SortPairs, FillVectorSortsLikeStdVector) {
  std::mt19937_64 rng(5);
  std::uniform_int_distribution<std::uint64_t> any;
  std::uniform_int_distribution<std::uint64_t> narrow(0, (1u << 11) - 1);  // one 11-bit pass, two 8-bit ones
  for (const std::size_t n : {std::size_t{100}, std::size_t{70000}, std::size_t{2 * 65536 + 9}}) {
    for (const bool one_pass : {false, true}) {
      for (const bool shuffled : {false, true}) {
        const auto v = make_pairs<std::uint64_t>(
            n, [&] { return one_pass ? narrow(rng) : any(rng); }, shuffled, rng);
        Pairs<std::uint64_t> expected = v;
        std::sort(expected.begin(), expected.end());
        core::FillVector<std::pair<std::uint64_t, std::uint32_t>> f(n);  // unwritten until the copy
        std::copy(v.begin(), v.end(), f.begin());
        tbb::task_arena(2).execute([&] { core::sort_pairs(f); });
        ASSERT_EQ(f.size(), n);
        EXPECT_TRUE(std::equal(f.begin(), f.end(), expected.begin())) << "n = " << n;
      }
    }
  }
}

TEST(SortPairs, AllKeysEqualLeavesValueOrder) {
  std::mt19937_64 rng(3);
  const auto v = make_pairs<std::uint64_t>(
      70000, [] { return std::uint64_t{42}; }, false, rng);
  auto sorted = v;
  core::sort_pairs(sorted);
  EXPECT_TRUE(sorted == v);
}

TEST(SortEqualKeyRuns, CompletesTheKeyOrderLikeOneFullSort) {
  // Keys with runs of every length (single pairs, short runs, and runs past
  // the parallel threshold of 4,096), a secondary value per index, ties by
  // index: the result must be std::sort's by (key, secondary, index), at 1
  // and 4 threads.
  std::mt19937_64 rng(43);
  Pairs<std::uint64_t> v;
  std::vector<std::uint32_t> secondary;
  const std::size_t run_lengths[] = {1, 1, 2, 3, 7, 1, 5000, 1, 40, 9000, 2, 1};
  for (int round = 0; round < 20; ++round)
    for (const std::size_t length : run_lengths) {
      const std::uint64_t key = rng() >> 20;
      for (std::size_t i = 0; i < length; ++i) {
        v.push_back({key, static_cast<std::uint32_t>(v.size())});
        secondary.push_back(static_cast<std::uint32_t>(rng() % 50));
      }
    }
  core::sort_pairs(v);
  const auto full = [&](const std::pair<std::uint64_t, std::uint32_t>& a,
                        const std::pair<std::uint64_t, std::uint32_t>& b) {
    if (a.first != b.first) return a.first < b.first;
    const std::uint32_t sa = secondary[a.second], sb = secondary[b.second];
    return sa != sb ? sa < sb : a.second < b.second;
  };
  Pairs<std::uint64_t> expected = v;
  std::sort(expected.begin(), expected.end(), full);
  for (const int threads : {1, 4}) {
    Pairs<std::uint64_t> got = v;
    tbb::task_arena(threads).execute([&] {
      core::sort_equal_key_runs(got, [&](const auto& a, const auto& b) {
        const std::uint32_t sa = secondary[a.second], sb = secondary[b.second];
        return sa != sb ? sa < sb : a.second < b.second;
      });
    });
    EXPECT_TRUE(got == expected) << "threads = " << threads;
  }
}

}  // namespace
}  // namespace ember::test
