// The solid path's cache of built triangles (core/solid_cuts.hpp,
// PolygonCache): each id's triangle as assign_triangle builds it, built once
// while the cache holds it, and kept across triangles with few partners
// until it passes kKeep.
#include <gtest/gtest.h>

#include "core/route/solid/solid_cuts.hpp"

namespace ember::core {
namespace {

GridTriangles strip_of_triangles(std::size_t n) {
  GridTriangles grid;
  grid.corners.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    const auto x = static_cast<std::int64_t>(i);
    grid.corners[i] = {IntPoint{x, 0, 0}, IntPoint{x + 1, 0, 0}, IntPoint{x, 1, static_cast<std::int64_t>(i % 5)}};
  }
  return grid;
}

TEST(PolygonCache, BuildsEachTriangleOnceAndKeepsThemForTrianglesWithFewPartners) {
  const GridTriangles grid = strip_of_triangles(PolygonCache::kKeep + 200);
  PolygonCache cache(grid);
  for (std::uint32_t id = 0; id < 1000; ++id) {
    const Polygon& p = cache.get(id);
    Polygon want;
    ASSERT_TRUE(assign_triangle(grid.corners[id][0], grid.corners[id][1], grid.corners[id][2], want));
    EXPECT_EQ(p.vertices.size(), 3u);
    EXPECT_EQ(p.edges, want.edges);
    EXPECT_TRUE(p.support == want.support);
  }
  for (std::uint32_t id = 0; id < 1000; ++id) cache.get(id);  // all held: nothing built again
  EXPECT_EQ(cache.size(), 1000u);
  // A triangle with one partner does not empty a cache below kKeep (the
  // 200-cube pile built its 2,400 triangles 358k times when it did).
  cache.reset_if_full(1);
  EXPECT_EQ(cache.size(), 1000u);
  for (std::uint32_t id = 1000; id <= PolygonCache::kKeep; ++id) cache.get(id);
  EXPECT_EQ(cache.size(), PolygonCache::kKeep + 1);
  // Past kKeep it is emptied unless the next triangle needs that many.
  cache.reset_if_full(PolygonCache::kKeep);
  EXPECT_EQ(cache.size(), PolygonCache::kKeep + 1);
  cache.reset_if_full(1);
  EXPECT_EQ(cache.size(), 0u);
  const Polygon& again = cache.get(7);
  EXPECT_EQ(again.vertices.size(), 3u);
  EXPECT_EQ(cache.size(), 1u);
}

}  // namespace
}  // namespace ember::core
