// Step 2b of the mesh stage (core/mesh/pass_through.cpp): a whole input
// triangle skips the region steps only when nothing could join it there.
#include <gtest/gtest.h>

#include <algorithm>
#include <vector>

#include "core/output/output_vertices.hpp"
#include "core/output/exact_weld.hpp"
#include "core/output/tjunctions.hpp"
#include "core/output/pass_through.hpp"
#include "core/output/vertex_index.hpp"

namespace ember::core {
namespace {

using Tri = std::array<IntPoint, 3>;

/// Runs steps 1, 2 and 2b on unbuilt triangles (corners counter-clockwise
/// seen from outside).
std::vector<char> passes(const std::vector<Tri>& tris) {
  std::vector<OutputPolygon> polys(tris.size());
  for (std::uint32_t i = 0; i < tris.size(); ++i) {
    polys[i].corners = &tris[i];
    polys[i].id = i;
  }
  const Quantizer q = Quantizer::fit_box({-10, -10, -10}, {10, 10, 10});
  const OutputVertices verts = exact_weld(polys, q);
  const VertexIndex index = index_output_vertices(polys, verts);
  const EdgePairs pairs = group_edges_by_pair(verts.corners);
  std::size_t inserted = 0;
  const Cycles cycles = insert_tjunction_vertices(polys, verts, index, pairs, inserted);
  return pass_through_triangles(polys, verts, pairs, cycles);
}

std::vector<Tri> octahedron() {
  const IntPoint px{4, 0, 0}, nx{-4, 0, 0}, py{0, 4, 0}, ny{0, -4, 0}, pz{0, 0, 4}, nz{0, 0, -4};
  return {{px, py, pz}, {py, nx, pz}, {nx, ny, pz}, {ny, px, pz},
          {py, px, nz}, {nx, py, nz}, {ny, nx, nz}, {px, ny, nz}};
}

TEST(PassThrough, TrianglesWithoutCoplanarNeighboursPass) {
  const std::vector<char> p = passes(octahedron());
  EXPECT_EQ(std::count(p.begin(), p.end(), 1), 8);
}

TEST(PassThrough, HalvesOfOneFaceDoNot) {
  // A square pyramid: the base is two coplanar triangles sharing a diagonal,
  // which step 3 merges; the four sides pass.
  const IntPoint a{0, 0, 0}, b{4, 0, 0}, c{4, 4, 0}, d{0, 4, 0}, apex{2, 2, 3};
  const std::vector<Tri> pyramid{{a, c, b}, {a, d, c}, {a, b, apex}, {b, c, apex}, {c, d, apex}, {d, a, apex}};
  const std::vector<char> p = passes(pyramid);
  EXPECT_EQ(p, (std::vector<char>{0, 0, 1, 1, 1, 1}));
}

TEST(PassThrough, AVertexInsertedIntoAnEdgeStopsIt) {
  // An octahedron whose top-front face is split in two at the midpoint of
  // its lower edge px-py: the neighbour across that edge (px, py, nz side)
  // gains the midpoint and must go through the region steps; the two halves
  // are coplanar neighbours of each other.
  std::vector<Tri> tris = octahedron();
  const IntPoint px{4, 0, 0}, py{0, 4, 0}, pz{0, 0, 4}, mid{2, 2, 0};
  tris[0] = {px, mid, pz};
  tris.push_back({mid, py, pz});
  const std::vector<char> p = passes(tris);
  EXPECT_EQ(p[0], 0);
  EXPECT_EQ(p[8], 0);
  EXPECT_EQ(p[4], 0) << "the face across the split edge gained a vertex";
  EXPECT_EQ(p[1], 1);
  EXPECT_EQ(p[3], 1);
  EXPECT_EQ(p[6], 1);
}

}  // namespace
}  // namespace ember::core
