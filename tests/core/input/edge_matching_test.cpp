// for_each_edge (edge_matching.hpp): every undirected edge once, with all of its
// uses in a fixed order, whatever the thread count; checked against a
// brute-force grouping on inputs that span several blocks and buckets of
// its two-level counting sort.
#include <gtest/gtest.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <array>
#include <cstdint>
#include <map>
#include <mutex>
#include <random>
#include <utility>
#include <vector>

#include "core/input/edge_matching.hpp"

namespace ember::core {
namespace {

using Uses = std::vector<std::array<std::uint32_t, 4>>;  // {hi, tri, forward, edge} in the order given
using Edges = std::map<std::pair<std::uint32_t, std::uint32_t>, Uses>;

/// Random triangles over `vertices` ids, some with a repeated corner (a
/// collapsed edge and an edge used twice by one triangle).
std::vector<std::array<std::uint32_t, 3>> random_triangles(std::size_t n, std::uint32_t vertices, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_int_distribution<std::uint32_t> id(0, vertices - 1);
  std::vector<std::array<std::uint32_t, 3>> tris(n);
  for (auto& t : tris) {
    t = {id(rng), id(rng), id(rng)};
    if (rng() % 50 == 0) t[2] = t[0];
  }
  return tris;
}

/// What for_each_edge must report: per undirected edge {lo, hi}, its uses by
/// triangle, then by edge of the triangle.
Edges reference(const std::vector<std::array<std::uint32_t, 3>>& tris) {
  Edges edges;
  for (std::uint32_t t = 0; t < tris.size(); ++t)
    for (std::uint32_t e = 0; e < 3; ++e) {
      const std::uint32_t a = tris[t][e], b = tris[t][(e + 1) % 3];
      if (a != b) edges[{std::min(a, b), std::max(a, b)}].push_back({std::max(a, b), t, a < b, e});
    }
  return edges;  // pushed in (triangle, edge) order already
}

Edges reported(const std::vector<std::array<std::uint32_t, 3>>& tris, std::uint32_t vertices, int threads) {
  WeldedTriangles welded{tris, vertices};
  Edges edges;
  std::mutex mutex;
  bool twice = false;
  tbb::task_arena(threads).execute([&] {
    for_each_edge(welded, [&](std::span<const EdgeUse> uses) {
      const std::array<std::uint32_t, 3>& t = tris[uses[0].tri];
      const std::uint32_t a = t[uses[0].edge], b = t[(uses[0].edge + 1) % 3];
      Uses list;
      for (const EdgeUse& u : uses) list.push_back({u.hi, u.tri, u.forward, u.edge});
      const std::lock_guard<std::mutex> lock(mutex);
      twice |= !edges.emplace(std::pair{std::min(a, b), std::max(a, b)}, std::move(list)).second;
    });
  });
  EXPECT_FALSE(twice) << "an edge was reported more than once";
  return edges;
}

TEST(ForEachEdge, ReportsEveryEdgeOnceWithItsUsesInTriangleOrder) {
  // 40k triangles: three blocks of the count; 20k ids: five buckets.
  constexpr std::uint32_t kVertices = 20000;
  const auto tris = random_triangles(40000, kVertices, 7);
  const Edges want = reference(tris);
  ASSERT_GT(want.size(), 100000u);
  for (const int threads : {1, 4}) EXPECT_EQ(reported(tris, kVertices, threads), want) << threads << " threads";
}

TEST(ForEachEdge, SharedEdgesGroupAllTheirUses) {
  // Few ids: most edges are used by several triangles, in both directions.
  constexpr std::uint32_t kVertices = 60;
  const auto tris = random_triangles(20000, kVertices, 11);
  const Edges want = reference(tris);
  std::size_t shared = 0;
  for (const auto& [edge, uses] : want) shared += uses.size() > 2;
  ASSERT_GT(shared, want.size() / 2);
  EXPECT_EQ(reported(tris, kVertices, 4), want);
}

}  // namespace
}  // namespace ember::core
