// The mesh stage's exact weld (core/mesh/exact_weld.cpp): one id per distinct
// exact point, numbered by first appearance. With the set-up's input vertex
// ids, unbuilt triangles are welded through their vertices instead of corner
// by corner; the result must be the same to the last id, and right against
// an exact all-pairs check.
#include <gtest/gtest.h>

#include <random>
#include <vector>

#include "core/output/output_vertices.hpp"
#include "core/output/exact_weld.hpp"
#include "geometry/clip.hpp"
#include "geometry/exact_order.hpp"
#include "geometry/polygon.hpp"

namespace ember::core {
namespace {

/// Two operands over one shared set of grid points (so equal points of
/// different operands have different input ids), output as a mix of unbuilt
/// triangles, built copies with grid corners, and clipped pieces whose cut
/// corners are not grid points (and repeat: both halves of a cut share them).
struct WeldCase {
  std::vector<IntPoint> points;
  std::vector<std::array<IntPoint, 3>> corners;      // by triangle id
  std::vector<std::array<std::uint32_t, 3>> vertex;  // by triangle id: per-operand welded ids
  std::vector<OutputPolygon> polys;
};

WeldCase make_case(std::uint32_t seed) {
  std::mt19937_64 rng(seed);
  WeldCase c;
  std::uniform_int_distribution<std::int64_t> coord(-40, 40);
  for (int i = 0; i < 60; ++i) c.points.push_back({coord(rng), coord(rng), coord(rng)});
  std::uniform_int_distribution<std::uint32_t> pick(0, 59);
  while (c.corners.size() < 300) {
    const std::array<std::uint32_t, 3> v{pick(rng), pick(rng), pick(rng)};
    const std::array<IntPoint, 3> t{c.points[v[0]], c.points[v[1]], c.points[v[2]]};
    if (grid_normal(t[0], t[1], t[2]) == std::array<std::int64_t, 3>{0, 0, 0}) continue;
    c.corners.push_back(t);
    c.vertex.push_back(v);  // the point index is a valid per-operand weld: equal ids iff equal positions
  }
  c.polys.reserve(2 * c.corners.size());
  for (std::uint32_t t = 0; t < c.corners.size(); ++t) {
    OutputPolygon base;
    base.corners = &c.corners[t];
    base.id = t;
    base.operand = t % 2;
    switch (rng() % 3) {
      case 0: c.polys.push_back(std::move(base)); break;  // unbuilt
      case 1: {
        const Polygon tri = *make_triangle(c.corners[t][0], c.corners[t][1], c.corners[t][2]);
        base.vertices.assign(tri.vertices.begin(), tri.vertices.end());
        c.polys.push_back(std::move(base));
        break;
      }
      default: {
        const Polygon tri = *make_triangle(c.corners[t][0], c.corners[t][1], c.corners[t][2]);
        Polygon neg, pos;
        const int axis = static_cast<int>(rng() % 3);
        if (clip(tri, axis_plane(axis, coord(rng)), neg, pos) != ClipSide::Both) {
          c.polys.push_back(std::move(base));
          break;
        }
        for (const Polygon* half : {&neg, &pos}) {
          OutputPolygon o;
          o.corners = base.corners;
          o.id = base.id;
          o.operand = base.operand;
          o.vertices.assign(half->vertices.begin(), half->vertices.end());
          c.polys.push_back(std::move(o));
        }
      }
    }
  }
  return c;
}

TEST(ExactWeld, InputVertexIdsGiveTheSameIdsAsWeldingEveryCorner) {
  const Quantizer q = Quantizer::fit_box({-1, -1, -1}, {1, 1, 1});
  for (std::uint32_t seed = 1; seed <= 5; ++seed) {
    const WeldCase c = make_case(seed);
    InputTopology ids;
    ids.by_triangle = c.vertex;
    ids.operand_base = {0, 60, 120};  // operand o's vertex v is o * 60 + v
    const OutputVertices plain = exact_weld(c.polys, q);
    const OutputVertices fast = exact_weld(c.polys, q, &ids);
    ASSERT_EQ(plain.corners.offsets, fast.corners.offsets);
    ASSERT_EQ(plain.corners.ids, fast.corners.ids) << "seed " << seed;
    ASSERT_EQ(plain.exact.size(), fast.exact.size());
    for (std::size_t v = 0; v < plain.exact.size(); ++v) {
      EXPECT_TRUE(same_point(plain.exact[v], fast.exact[v]));
      EXPECT_EQ(plain.rounded[v].x, fast.rounded[v].x);
      EXPECT_EQ(plain.rounded[v].y, fast.rounded[v].y);
      EXPECT_EQ(plain.rounded[v].z, fast.rounded[v].z);
    }
    // Against the definition: equal ids iff equal exact points, and ids in
    // order of first appearance.
    std::vector<Point> corner_point;
    for (const OutputPolygon& p : c.polys)
      for (std::size_t k = 0; k < corner_count(p); ++k)
        corner_point.push_back(unbuilt(p) ? to_point((*p.corners)[k]) : p.vertices[k]);
    ASSERT_EQ(corner_point.size(), fast.corners.ids.size());
    std::uint32_t next = 0;
    for (std::size_t a = 0; a < corner_point.size(); ++a) {
      const std::uint32_t id = fast.corners.ids[a];
      if (id == next) ++next;
      ASSERT_LT(id, next) << "ids are not numbered by first appearance";
      for (std::size_t b = 0; b < a; ++b)
        ASSERT_EQ(same_point(corner_point[a], corner_point[b]), id == fast.corners.ids[b]) << a << " " << b;
    }
    EXPECT_EQ(next, fast.exact.size());
  }
}

}  // namespace
}  // namespace ember::core
