// The mesh stage's bookkeeping for collinear vertices (core/mesh/collinear.cpp):
// removal on both sides, and restore_vertices, which puts removed vertices
// back around a region that has to fall back to piece-by-piece triangulation
// so that the fallback stays watertight. No real input falls back today, so
// the restore path is exercised here on hand-built regions.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <random>
#include <vector>

#include "core/output/output_vertices.hpp"
#include "core/output/regions.hpp"
#include "core/output/collinear.hpp"
#include "core/output/region_triangulation.hpp"
#include "core/output/diagonals.hpp"
#include "core/output/vertex_index.hpp"

namespace ember::core {
namespace {

/// Appends a closed loop of boundary edges for `region` (ids in order).
void add_loop(Regions& r, std::uint32_t region, const std::vector<std::uint32_t>& ids) {
  const auto base = static_cast<std::uint32_t>(r.edges.size());
  const auto n = static_cast<std::uint32_t>(ids.size());
  for (std::uint32_t k = 0; k < n; ++k) r.edges.push_back({ids[k], ids[(k + 1) % n], region, base + (k + 1) % n, true});
  r.edge_begin.push_back(static_cast<std::uint32_t>(r.edges.size()));
}

/// The loop of alive edges through the region's first alive edge, as vertex ids.
std::vector<std::uint32_t> walk(const Regions& r, std::uint32_t region) {
  std::uint32_t start = r.edge_begin[region];
  while (!r.edges[start].alive) ++start;
  std::vector<std::uint32_t> ids;
  std::uint32_t e = start;
  do {
    ids.push_back(r.edges[e].from);
    e = r.edges[e].next;
  } while (e != start && ids.size() < 100);
  return ids;
}

/// Region 0 in the plane z = 0 and region 1 in y = 0 share the line from 0
/// to 2, which vertices 1 and 8 split: 0->1->8->2 in region 0 and
/// 2->8->1->0 in region 1. Region 2 (x = 5) is unrelated.
Regions two_planes_sharing_a_split_edge() {
  Regions r;
  r.edge_begin.push_back(0);
  r.regions = {{axis_plane(2, 0), 0}, {axis_plane(1, 0), 1}, {axis_plane(0, 5), 2}};
  r.piece_ids = {0, 1, 2};
  r.piece_begin = {0, 1, 2, 3};
  add_loop(r, 0, {0, 1, 8, 2, 3, 4});
  add_loop(r, 1, {2, 8, 1, 0, 5, 6});
  add_loop(r, 2, {10, 11, 12});
  return r;
}

const std::vector<char> kNothingPinned(13, 0);

TEST(MeshStage, CollinearVerticesAreRemovedOnBothSides) {
  Regions r = two_planes_sharing_a_split_edge();
  const std::vector<Removal> removed = remove_collinear_vertices(r, 13, kNothingPinned);
  ASSERT_EQ(removed.size(), 2u);
  EXPECT_EQ(removed[0].v, 1u);
  EXPECT_EQ(removed[1].v, 8u);
  EXPECT_EQ(walk(r, 0), (std::vector<std::uint32_t>{0, 2, 3, 4}));
  EXPECT_EQ(walk(r, 1), (std::vector<std::uint32_t>{2, 0, 5, 6}));
  EXPECT_EQ(walk(r, 2), (std::vector<std::uint32_t>{10, 11, 12}));
}

TEST(MeshStage, PinnedVerticesAreKept) {
  // Vertex 8 is a corner of a pass-through triangle (step 2b), whose edges
  // the regions do not see: it stays on both sides; vertex 1 still goes.
  Regions r = two_planes_sharing_a_split_edge();
  std::vector<char> pinned(13, 0);
  pinned[8] = 1;
  const std::vector<Removal> removed = remove_collinear_vertices(r, 13, pinned);
  ASSERT_EQ(removed.size(), 1u);
  EXPECT_EQ(removed[0].v, 1u);
  EXPECT_EQ(walk(r, 0), (std::vector<std::uint32_t>{0, 8, 2, 3, 4}));
  EXPECT_EQ(walk(r, 1), (std::vector<std::uint32_t>{2, 8, 0, 5, 6}));
}

TEST(MeshStage, ParallelPlanesKeepTheirVertices) {
  // The same loops with region 1 parallel to region 0 (z = 1): the shared
  // ids no longer mean a shared line between two planes; nothing is removed.
  Regions r = two_planes_sharing_a_split_edge();
  r.regions[1].plane = axis_plane(2, 1);
  EXPECT_TRUE(remove_collinear_vertices(r, 13, kNothingPinned).empty());
}

TEST(MeshStage, RestoringAroundAFailedRegionPutsVerticesBackOnBothSides) {
  for (const std::uint32_t failing : {0u, 1u}) {
    SCOPED_TRACE(failing);
    Regions r = two_planes_sharing_a_split_edge();
    const std::vector<Removal> removed = remove_collinear_vertices(r, 13, kNothingPinned);
    ASSERT_EQ(removed.size(), 2u);
    std::vector<char> failed(3, 0), undone(removed.size(), 0);
    failed[failing] = 1;
    // Both removals touch the failed region; the second also saw the first's
    // edges. Both come back, and the other sharing region must be redone.
    const std::vector<std::uint32_t> changed = restore_vertices(r, removed, failed, undone);
    EXPECT_EQ(changed, (std::vector<std::uint32_t>{1u - failing}));
    EXPECT_EQ(undone, (std::vector<char>{1, 1}));
    EXPECT_EQ(walk(r, 0), (std::vector<std::uint32_t>{0, 1, 8, 2, 3, 4}));
    EXPECT_EQ(walk(r, 1), (std::vector<std::uint32_t>{2, 8, 1, 0, 5, 6}));
    // A second call has nothing left to put back.
    EXPECT_TRUE(restore_vertices(r, removed, failed, undone).empty());
  }
}

TEST(MeshStage, RestoringAroundAnUnrelatedRegionChangesNothing) {
  Regions r = two_planes_sharing_a_split_edge();
  const std::vector<Removal> removed = remove_collinear_vertices(r, 13, kNothingPinned);
  std::vector<char> failed{0, 0, 1}, undone(removed.size(), 0);
  EXPECT_TRUE(restore_vertices(r, removed, failed, undone).empty());
  EXPECT_EQ(undone, (std::vector<char>{0, 0}));
  EXPECT_EQ(walk(r, 0), (std::vector<std::uint32_t>{0, 2, 3, 4}));
}

/// Grid points as output vertices (exact and rounded alike).
OutputVertices grid_vertices(const std::vector<IntPoint>& points) {
  OutputVertices v;
  for (const IntPoint& p : points) {
    v.exact.push_back(to_point(p));
    v.rounded.push_back({static_cast<double>(p.x), static_cast<double>(p.y), static_cast<double>(p.z)});
  }
  return v;
}

TEST(MeshStage, DiagonalThroughAUsedVertexIsSplit) {
  // Square 0-1-2-3 in z = 0 as two triangles on the diagonal 0-2; vertex 4
  // sits in the middle of the diagonal (another part touching the face),
  // vertex 5 a quarter of the way, unused; vertex 6 is off the plane.
  const OutputVertices verts =
      grid_vertices({{0, 0, 0}, {4, 0, 0}, {4, 4, 0}, {0, 4, 0}, {2, 2, 0}, {1, 1, 0}, {3, 3, 1}});
  std::vector<std::uint32_t> all{0, 1, 2, 3, 4, 5, 6};
  const VertexIndex index(verts.rounded, all, 1.0);
  const Plane up = axis_plane(2, 0);  // normal +z: the triangles run counter-clockwise seen from above
  std::vector<std::array<std::uint32_t, 3>> tris{{0, 1, 2}, {0, 2, 3}};
  std::vector<char> used{1, 1, 1, 1, 1, 0, 1};
  EXPECT_EQ(split_diagonals(up, verts, index, used, tris), 1u);
  for (auto& t : tris) std::rotate(t.begin(), std::min_element(t.begin(), t.end()), t.end());  // same cycles
  std::sort(tris.begin(), tris.end());
  EXPECT_EQ(tris, (std::vector<std::array<std::uint32_t, 3>>{{0, 1, 4}, {0, 4, 3}, {1, 2, 4}, {2, 3, 4}}));
  // Unused vertices are not inserted.
  std::vector<std::array<std::uint32_t, 3>> again{{0, 1, 2}, {0, 2, 3}};
  used[4] = 0;
  EXPECT_EQ(split_diagonals(up, verts, index, used, again), 0u);
  EXPECT_EQ(again.size(), 2u);
  // Two used points on the diagonal: both, in order.
  std::vector<std::array<std::uint32_t, 3>> two{{0, 1, 2}, {0, 2, 3}};
  used[4] = used[5] = 1;
  EXPECT_EQ(split_diagonals(up, verts, index, used, two), 2u);
  EXPECT_EQ(two.size(), 6u);
}

TEST(MeshStage, DiagonalThroughACornerOfTheSameTrianglesIsSplit) {
  // A square like the one above (twice as large) on the diagonal 0-2, plus a third triangle
  // 4-5-6 of the same list whose corner 4 is the diagonal's midpoint: a
  // corner of the list's own triangles is a vertex like any other.
  const OutputVertices verts =
      grid_vertices({{0, 0, 0}, {8, 0, 0}, {8, 8, 0}, {0, 8, 0}, {4, 4, 0}, {6, 3, 0}, {6, 5, 0}});
  std::vector<std::uint32_t> all{0, 1, 2, 3, 4, 5, 6};
  const VertexIndex index(verts.rounded, all, 1.0);
  const Plane up = axis_plane(2, 0);
  const std::vector<char> used(7, 1);
  std::vector<std::array<std::uint32_t, 3>> tris{{0, 1, 2}, {0, 2, 3}, {4, 5, 6}};
  EXPECT_EQ(split_diagonals(up, verts, index, used, tris), 1u);
  EXPECT_EQ(tris.size(), 5u);
  // Without the corner's triangle nothing touches the diagonal.
  std::vector<std::array<std::uint32_t, 3>> square{{0, 1, 2}, {0, 2, 3}};
  const std::vector<char> only_square{1, 1, 1, 1, 0, 1, 1};
  EXPECT_EQ(split_diagonals(up, verts, index, only_square, square), 0u);
  EXPECT_EQ(square.size(), 2u);
}

TEST(MeshStage, HolesThatHideEachOtherAreBridgedInOrder) {
  // A square region in z = 0 with five square holes: the central one (A)
  // sees no outer corner past the four others, which sit on its lines of
  // sight. Bridging the holes in the order given (A first) finds no outer
  // vertex for A; in decreasing order of their largest vertex every hole
  // sees the outer loop or a hole already joined to it.
  std::vector<IntPoint> pts{{0, 0, 0}, {100, 0, 0}, {100, 100, 0}, {0, 100, 0}};
  const std::vector<std::array<std::int64_t, 4>> squares{
      {48, 48, 52, 52}, {70, 70, 80, 80}, {70, 20, 82, 32}, {20, 70, 32, 82}, {20, 20, 30, 30}};  // A first
  Regions r;
  r.edge_begin.push_back(0);
  r.regions = {{axis_plane(2, 0), 0}};
  r.piece_ids = {0};
  r.piece_begin = {0, 1};
  std::vector<std::vector<std::uint32_t>> loops{{0, 1, 2, 3}};
  for (const auto& [x0, y0, x1, y1] : squares) {
    const auto first = static_cast<std::uint32_t>(pts.size());
    for (const IntPoint& p : {IntPoint{x0, y0, 0}, IntPoint{x0, y1, 0}, IntPoint{x1, y1, 0}, IntPoint{x1, y0, 0}})
      pts.push_back(p);  // clockwise seen from +z: a hole
    loops.push_back({first, first + 1, first + 2, first + 3});
  }
  // All loops in one region: one edge range, each loop linked to itself.
  for (const auto& loop : loops) {
    const auto base = static_cast<std::uint32_t>(r.edges.size());
    const auto n = static_cast<std::uint32_t>(loop.size());
    for (std::uint32_t k = 0; k < n; ++k) r.edges.push_back({loop[k], loop[(k + 1) % n], 0, base + (k + 1) % n, true});
  }
  r.edge_begin.push_back(static_cast<std::uint32_t>(r.edges.size()));
  const OutputVertices verts = grid_vertices(pts);
  std::vector<std::array<std::uint32_t, 3>> tris;
  ASSERT_TRUE(triangulate_region(r, 0, verts, tris));
  // Counter-clockwise triangles covering the square minus the holes.
  std::int64_t twice_area = 0;
  for (const auto& t : tris) {
    const IntPoint &a = pts[t[0]], &b = pts[t[1]], &c = pts[t[2]];
    const std::int64_t cross = (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x);
    EXPECT_GT(cross, 0);
    twice_area += cross;
  }
  std::int64_t holes = 0;
  for (const auto& [x0, y0, x1, y1] : squares) holes += (x1 - x0) * (y1 - y0);
  EXPECT_EQ(twice_area, 2 * (100 * 100 - holes));
}

/// Triangulates `loop` walking round it for every ear and through the grid
/// (loop_grid.hpp), and expects the same triangles (and success) both ways.
void expect_same_ears_through_the_grid(const OutputVertices& verts, const std::vector<std::uint32_t>& loop,
                                       std::size_t& triangles) {
  const Plane up = axis_plane(2, 0);
  std::vector<std::array<std::uint32_t, 3>> walked, gridded;
  const bool walked_ok = triangulate_loop(loop, up, verts, walked, SIZE_MAX);
  const bool gridded_ok = triangulate_loop(loop, up, verts, gridded, 4);
  EXPECT_TRUE(walked_ok);
  EXPECT_EQ(gridded_ok, walked_ok);
  EXPECT_EQ(gridded, walked);
  triangles += walked.size();
}

TEST(MeshStage, LongLoopsClipTheSameEarsThroughTheGrid) {
  // The ear clipper's grid only narrows which vertices each ear is tested
  // against: a comb (deep reflex teeth), star-shaped loops of random radii
  // (with collinear runs: radii on a coarse grid) at small and at large
  // coordinates, and a square with a star-shaped hole joined by a bridge
  // (its two end points appear twice) give the same triangles either way.
  std::size_t triangles = 0;
  {  // the comb: 60 teeth of height 50 on a base of height 2
    std::vector<IntPoint> pts{{0, 0, 0}, {240, 0, 0}, {240, 52, 0}};
    for (std::int64_t t = 59; t >= 0; --t)
      for (const IntPoint& p : {IntPoint{4 * t + 3, 52, 0}, IntPoint{4 * t + 2, 2, 0}, IntPoint{4 * t + 1, 52, 0}})
        pts.push_back(p);
    pts.push_back({0, 52, 0});
    std::vector<std::uint32_t> loop(pts.size());
    for (std::uint32_t i = 0; i < loop.size(); ++i) loop[i] = i;
    expect_same_ears_through_the_grid(grid_vertices(pts), loop, triangles);
  }
  std::mt19937 rng(47);
  for (const std::int64_t offset : {std::int64_t{0}, std::int64_t{1} << 24}) {
    for (const int n : {70, 300, 1000}) {  // star-shaped around the offset: counter-clockwise by angle
      std::uniform_int_distribution<int> radius(2, 12);
      std::vector<IntPoint> pts;
      for (int i = 0; i < n; ++i) {
        const double angle = 2 * M_PI * i / n;
        const double r = 1000.0 * radius(rng);
        pts.push_back({offset + std::llround(r * std::cos(angle)), offset + std::llround(r * std::sin(angle)), 0});
      }
      std::vector<std::uint32_t> loop(pts.size());
      for (std::uint32_t i = 0; i < loop.size(); ++i) loop[i] = i;
      expect_same_ears_through_the_grid(grid_vertices(pts), loop, triangles);
    }
  }
  {  // a square with a star-shaped hole (clockwise), bridged from corner 0 to the hole's vertex 0
    std::vector<IntPoint> pts{{-20000, -20000, 0}, {20000, -20000, 0}, {20000, 20000, 0}, {-20000, 20000, 0}};
    std::uniform_int_distribution<int> radius(3, 9);
    const int n = 200;
    for (int i = 0; i < n; ++i) {
      const double angle = -2 * M_PI * i / n + 1.25 * M_PI;  // from the lower left, clockwise
      const double r = 1000.0 * radius(rng);
      pts.push_back({std::llround(r * std::cos(angle)), std::llround(r * std::sin(angle)), 0});
    }
    std::vector<std::uint32_t> loop{0};
    for (std::uint32_t i = 0; i <= static_cast<std::uint32_t>(n); ++i) loop.push_back(4 + i % n);
    for (const std::uint32_t corner : {0u, 1u, 2u, 3u}) loop.push_back(corner);
    expect_same_ears_through_the_grid(grid_vertices(pts), loop, triangles);
  }
  EXPECT_GT(triangles, 2000u);
}

TEST(MeshStage, ShortLoopsClipTheSameEarsWithTheScanQueue) {
  // Loops of up to 16 vertices take their ears from a scan instead of a
  // heap (walking round them); through the grid they use the heap. Both
  // must clip the same ears in the same order, also where ears tie in
  // quality exactly (squares, a symmetric octagon, regular shapes on a
  // coarse grid) and where none is valid until a refill (reflex combs).
  std::size_t triangles = 0;
  const auto closed = [](std::size_t n) {
    std::vector<std::uint32_t> loop(n);
    for (std::uint32_t i = 0; i < n; ++i) loop[i] = i;
    return loop;
  };
  for (const std::vector<IntPoint>& pts : std::vector<std::vector<IntPoint>>{
           {{0, 0, 0}, {10, 0, 0}, {10, 10, 0}, {0, 10, 0}},
           {{0, 0, 0}, {30, 0, 0}, {30, 10, 0}, {0, 10, 0}},
           {{2, 0, 0}, {4, 0, 0}, {6, 2, 0}, {6, 4, 0}, {4, 6, 0}, {2, 6, 0}, {0, 4, 0}, {0, 2, 0}},
           {{0, 0, 0},
            {12, 0, 0},
            {12, 9, 0},
            {11, 1, 0},
            {9, 9, 0},
            {7, 1, 0},
            {5, 9, 0},
            {3, 1, 0},
            {1, 9, 0},
            {0, 9, 0}}})
    expect_same_ears_through_the_grid(grid_vertices(pts), closed(pts.size()), triangles);
  std::mt19937 rng(53);
  for (int round = 0; round < 400; ++round) {  // star-shaped, 4 to 16 vertices, radii on a coarse grid
    const int n = 4 + round % 13;
    std::uniform_int_distribution<int> radius(1, 4);
    std::vector<IntPoint> pts;
    for (int i = 0; i < n; ++i) {
      const double angle = 2 * M_PI * i / n;
      const double r = 10.0 * radius(rng);
      pts.push_back({std::llround(r * std::cos(angle)), std::llround(r * std::sin(angle)), 0});
    }
    bool repeated = false;  // a star whose rounding repeats a point is no simple loop
    for (std::size_t i = 0; i < pts.size(); ++i)
      for (std::size_t j = i + 1; j < pts.size(); ++j) repeated = repeated || pts[i] == pts[j];
    if (repeated) continue;
    expect_same_ears_through_the_grid(grid_vertices(pts), closed(pts.size()), triangles);
  }
  EXPECT_GT(triangles, 2000u);
}

}  // namespace
}  // namespace ember::core
