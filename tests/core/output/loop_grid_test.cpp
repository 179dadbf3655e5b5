// LoopGrid (src/core/mesh/loop_grid.hpp): the ear clipper's grid offers
// every point still in it that lies in a queried box, and no removed one.
#include "core/output/loop_grid.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <random>
#include <vector>

namespace ember::core {
namespace {

/// The points `grid` offers for the box [lo, hi] (f never says stop).
std::vector<std::uint32_t> offered(const LoopGrid& grid, const std::array<double, 3>& lo,
                                   const std::array<double, 3>& hi) {
  std::vector<std::uint32_t> out;
  EXPECT_FALSE(grid.any(lo, hi, [&](std::uint32_t i) {
    out.push_back(i);
    return false;
  }));
  std::sort(out.begin(), out.end());
  return out;
}

TEST(LoopGrid, OffersEveryPointLeftInTheBoxAndNoRemovedOne) {
  std::mt19937 rng(33);
  for (const double scale : {1.0, 1e7}) {
    const std::size_t n = 600;
    std::uniform_real_distribution<double> coord(-scale, scale);
    std::vector<std::array<double, 3>> pts(n);
    for (auto& p : pts) p = {coord(rng), coord(rng), 0.25 * coord(rng)};
    LoopGrid grid(n, [&](std::size_t i) -> const std::array<double, 3>& { return pts[i]; });
    std::vector<bool> removed(n, false);
    std::vector<std::uint32_t> order(n);
    for (std::uint32_t i = 0; i < n; ++i) order[i] = i;
    std::shuffle(order.begin(), order.end(), rng);
    std::size_t gone = 0;
    for (int round = 0; round < 6; ++round) {
      for (int q = 0; q < 40; ++q) {
        std::array<double, 3> lo{}, hi{};
        for (int a = 0; a < 3; ++a) {
          const double x = coord(rng), y = coord(rng);
          lo[a] = std::min(x, y);
          hi[a] = std::max(x, y);
        }
        const std::vector<std::uint32_t> got = offered(grid, lo, hi);
        for (const std::uint32_t i : got) EXPECT_FALSE(removed[i]) << "removed point " << i << " offered";
        EXPECT_TRUE(std::adjacent_find(got.begin(), got.end()) == got.end()) << "a point offered twice";
        for (std::uint32_t i = 0; i < n; ++i) {
          bool inside = !removed[i];
          for (int a = 0; a < 3; ++a) inside = inside && pts[i][a] >= lo[a] && pts[i][a] <= hi[a];
          if (inside) {
            EXPECT_TRUE(std::binary_search(got.begin(), got.end(), i)) << "point " << i << " missed";
          }
        }
      }
      for (std::size_t r = 0; r < n / 8; ++r, ++gone) {  // take out the next eighth, in random order
        grid.remove(order[gone]);
        removed[order[gone]] = true;
      }
    }
    // Everything but the last quarter is out: a box over all offers exactly the rest.
    const std::vector<std::uint32_t> rest = offered(grid, {-scale, -scale, -scale}, {scale, scale, scale});
    std::vector<std::uint32_t> expected(order.begin() + static_cast<std::ptrdiff_t>(gone), order.end());
    std::sort(expected.begin(), expected.end());
    EXPECT_EQ(rest, expected);
  }
}

TEST(LoopGrid, AnyStopsAtTheFirstPointTheCallerAccepts) {
  const std::vector<std::array<double, 3>> pts{{0, 0, 0}, {1, 1, 0}, {2, 2, 0}, {3, 3, 0}};
  LoopGrid grid(pts.size(), [&](std::size_t i) -> const std::array<double, 3>& { return pts[i]; });
  EXPECT_TRUE(grid.any({0, 0, 0}, {3, 3, 0}, [](std::uint32_t i) { return i == 2; }));
  grid.remove(2);
  EXPECT_FALSE(grid.any({0, 0, 0}, {3, 3, 0}, [](std::uint32_t i) { return i == 2; }));
}

}  // namespace
}  // namespace ember::core
