// parallel_select (src/core/parallel_select.hpp) must give a serial filter's
// result, in index order, at any thread count and across block boundaries
// (4096 indices per block); parallel_filled every entry the value.
#include <gtest/gtest.h>

#include <tbb/task_arena.h>

#include <cstdint>
#include <random>
#include <vector>

#include "core/parallel_select.hpp"

namespace ember::test {
namespace {

/// Sizes around the block boundaries, and one of many blocks.
constexpr std::size_t kSizes[] = {0, 1, 2, 4095, 4096, 4097, 8191, 8193, 100'003};

TEST(ParallelSelect, MatchesASerialFilterInOrder) {
  std::mt19937_64 rng(20221125);
  for (const std::size_t n : kSizes)
    for (const double density : {0.0, 0.01, 0.5, 1.0}) {
      std::vector<char> flag(n);
      std::bernoulli_distribution keep(density);
      for (auto& f : flag) f = keep(rng);
      std::vector<std::uint64_t> expected;
      for (std::size_t i = 0; i < n; ++i)
        if (flag[i]) expected.push_back(3 * i + 7);
      for (const int threads : {1, 2, 5}) {
        core::FillVector<std::uint64_t> got;
        tbb::task_arena(threads).execute([&] {
          got = core::parallel_select<std::uint64_t>(
              n, [&](std::size_t i) { return flag[i] != 0; }, [](std::size_t i) { return std::uint64_t{3 * i + 7}; });
        });
        ASSERT_EQ(std::vector<std::uint64_t>(got.begin(), got.end()), expected)
            << "n " << n << ", density " << density << ", threads " << threads;
      }
    }
}

TEST(ParallelSelect, IndicesWhereListsTheKeptIndicesAscending) {
  const std::size_t n = 50'000;
  std::vector<std::uint32_t> expected;
  for (std::uint32_t i = 0; i < n; ++i)
    if (i % 7 == 3 || i % 4096 == 0) expected.push_back(i);
  core::FillVector<std::uint32_t> got;
  tbb::task_arena(4).execute(
      [&] { got = core::parallel_indices_where(n, [](std::size_t i) { return i % 7 == 3 || i % 4096 == 0; }); });
  EXPECT_EQ(std::vector<std::uint32_t>(got.begin(), got.end()), expected);
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
