// parallel_select (src/core/parallel_select.hpp) must give a serial filter's
// result, in index order, at any thread count and across block boundaries
// (kSelectBlock indices per block), calling make only for kept indices;
// parallel_filled every entry the value.
#include <gtest/gtest.h>

#include <tbb/task_arena.h>

#include <atomic>
#include <cstdint>
#include <random>
#include <vector>

#include "core/support/parallel_select.hpp"

namespace ember::test {
namespace {

/// Sizes around the block boundaries, and one of many blocks.
constexpr std::size_t kB = core::kSelectBlock;
constexpr std::size_t kSizes[] = {0, 1, 2, kB - 1, kB, kB + 1, 2 * kB - 1, 2 * kB + 1, 24 * kB + 3};

/// A struct entry, like the kept triangles' (id, flip).
struct Entry {
  std::uint32_t id;
  bool odd;
  bool operator==(const Entry&) const = default;
};

TEST(ParallelSelect, MatchesASerialFilterInOrder) {
  std::mt19937_64 rng(20221125);
  for (const std::size_t n : kSizes)
    for (const double density : {0.0, 0.01, 0.5, 1.0}) {
      std::vector<char> flag(n);
      std::bernoulli_distribution keep(density);
      for (auto& f : flag) f = keep(rng);
      std::vector<Entry> expected;
      for (std::size_t i = 0; i < n; ++i)
        if (flag[i]) expected.push_back({static_cast<std::uint32_t>(3 * i + 7), i % 2 == 1});
      for (const int threads : {1, 2, 5}) {
        core::FillVector<Entry> got;
        std::atomic<bool> made_for_dropped{false};
        tbb::task_arena(threads).execute([&] {
          got = core::parallel_select<Entry>(
              n, [&](std::size_t i) { return flag[i] != 0; },
              [&](std::size_t i) {
                if (!flag[i]) made_for_dropped = true;
                return Entry{static_cast<std::uint32_t>(3 * i + 7), i % 2 == 1};
              });
        });
        ASSERT_EQ(std::vector<Entry>(got.begin(), got.end()), expected)
            << "n " << n << ", density " << density << ", threads " << threads;
        ASSERT_FALSE(made_for_dropped) << "make called for an index keep dropped";
      }
    }
}

TEST(ParallelSelect, IndicesWhereListsTheKeptIndicesAscending) {
  const std::size_t n = 50'000;
  const auto keep = [](std::size_t i) { return i % 7 == 3 || i % kB == 0; };
  std::vector<std::uint32_t> expected;
  for (std::uint32_t i = 0; i < n; ++i)
    if (keep(i)) expected.push_back(i);
  for (const int threads : {1, 2, 4}) {
    core::FillVector<std::uint32_t> got;
    tbb::task_arena(threads).execute([&] { got = core::parallel_indices_where(n, keep); });
    EXPECT_EQ(std::vector<std::uint32_t>(got.begin(), got.end()), expected) << "threads " << threads;
  }
}

TEST(ParallelSelect, FilledHoldsTheValueEverywhere) {
  for (const std::size_t n : kSizes) {
    core::FillVector<std::uint64_t> v;
    tbb::task_arena(3).execute([&] { v = core::parallel_filled<std::uint64_t>(n, UINT64_MAX - 5); });
    ASSERT_EQ(v.size(), n);
    for (std::size_t i = 0; i < n; ++i) ASSERT_EQ(v[i], UINT64_MAX - 5) << "n " << n << ", entry " << i;
  }
}

}  // namespace
}  // namespace ember::test
