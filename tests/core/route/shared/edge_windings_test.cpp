// Leaves hand winding numbers across shared input edges (core/edge_windings.hpp)
// instead of tracing every piece. The oracle is the leaf that traces every
// piece: both must emit exactly the same pieces with the same orientation.
// Each scene is solved as one leaf (every polygon sees every other), where
// the most values are handed on.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <random>
#include <vector>

#include "core/model/indicator.hpp"
#include "core/route/shared/edge_windings.hpp"
#include "core/model/output_polygon.hpp"
#include "core/model/solve_context.hpp"
#include "core/route/general/subproblem.hpp"
#include "core/route/general/leaf.hpp"
#include "geometry/exact_order.hpp"
#include "support/shapes.hpp"

namespace ember::core {
namespace {

using Tri = std::array<IntPoint, 3>;

struct Scene {
  std::vector<Tri> tris;
  std::vector<std::uint32_t> operand;
  std::size_t operands = 0;
  std::vector<char> closed;  ///< per operand
};

/// Adds a mesh's faces (fanned) on the integer grid, scaled and rounded;
/// faces that rounding makes collinear are dropped.
void add(Scene& s, const Mesh& m, double scale, bool closed = true) {
  const auto o = static_cast<std::uint32_t>(s.operands++);
  s.closed.push_back(closed ? 1 : 0);
  auto grid = [&](std::uint32_t v) {
    const Vec3d& p = m.vertices[v];
    return IntPoint{std::llround(p.x * scale), std::llround(p.y * scale), std::llround(p.z * scale)};
  };
  for (std::size_t f = 0; f < m.face_count(); ++f) {
    const auto face = m.face(f);
    for (std::size_t k = 1; k + 1 < face.size(); ++k) {
      const Tri t{grid(face[0]), grid(face[k]), grid(face[k + 1])};
      if (!supporting_plane(t[0], t[1], t[2])) continue;
      s.tris.push_back(t);
      s.operand.push_back(o);
    }
  }
}

std::vector<OutputPolygon> solve_as_one_leaf(const Scene& s, Operation op, const std::vector<char>& solid, bool share) {
  Subproblem pb;
  pb.box.lo = {INT64_MAX, INT64_MAX, INT64_MAX};
  pb.box.hi = {INT64_MIN, INT64_MIN, INT64_MIN};
  for (const Tri& t : s.tris)
    for (const IntPoint& c : t) {
      const std::array<std::int64_t, 3> p{c.x, c.y, c.z};
      for (int a = 0; a < 3; ++a) {
        pb.box.lo[a] = std::min(pb.box.lo[a], p[a] - 1);
        pb.box.hi[a] = std::max(pb.box.hi[a], p[a] + 1);
      }
    }
  for (int a = 0; a < 3; ++a) pb.ref.num[a] = 2 * pb.box.lo[a] + 1;  // a corner of the box: outside everything
  pb.ref.shift = 1;
  pb.ref_w.assign(s.operands, 0);
  for (std::uint32_t i = 0; i < s.tris.size(); ++i) {
    pb.soup.push_back(unbuilt_triangle(s.tris[i], i, s.operand[i]));
    materialize(pb.soup.back());
  }
  SolveContext ctx;
  ctx.operands = s.operands;
  ctx.op = op;
  ctx.inside = [&](const Wnv& w) {
    std::size_t count = 0;
    for (const int x : w) count += x != 0;
    return inside_by_count(op, 1, w.size(), count, w[0] != 0);
  };
  ctx.solid = solid;
  ctx.closed = s.closed;
  ctx.share_edge_windings = share;
  std::vector<OutputPolygon> out;
  solve_leaf(pb, ctx, out);
  return out;
}

/// Solves the scene with and without shared windings and compares; returns
/// how many pieces were emitted (some operations give nothing on twins).
std::size_t expect_same_leaf(const Scene& s, Operation op, const std::vector<char>& solid) {
  SCOPED_TRACE("operation " + std::to_string(static_cast<int>(op)) + ", solid flags " + std::to_string(solid[0]) +
               "..");
  const std::vector<OutputPolygon> traced = solve_as_one_leaf(s, op, solid, false);
  const std::vector<OutputPolygon> shared = solve_as_one_leaf(s, op, solid, true);
  EXPECT_EQ(shared.size(), traced.size());
  if (shared.size() != traced.size()) return traced.size();
  for (std::size_t i = 0; i < traced.size(); ++i) {
    const OutputPolygon &a = traced[i], &b = shared[i];
    EXPECT_EQ(a.id, b.id) << "piece " << i;
    EXPECT_EQ(a.flip, b.flip) << "piece " << i << " of triangle " << a.id << " is oriented differently";
    EXPECT_EQ(a.whole_piece, b.whole_piece) << "piece " << i;
    EXPECT_EQ(a.vertices.size(), b.vertices.size()) << "piece " << i;
    if (a.id != b.id || a.vertices.size() != b.vertices.size()) return traced.size();
    for (std::size_t v = 0; v < a.vertices.size(); ++v) EXPECT_TRUE(same_point(a.vertices[v], b.vertices[v]));
  }
  return traced.size();
}

constexpr Operation kOps[] = {Operation::Union, Operation::Intersection, Operation::Difference, Operation::Xor};

TEST(EdgeWindings, TwoSpheresSolidAndGeneral) {
  std::size_t emitted = 0;
  Scene s;
  add(s, test::icosphere({0, 0, 0}, 1, 2), 1000);
  add(s, test::icosphere({0.55, 0.3, 0.2}, 0.9, 2), 1000);
  for (const Operation op : kOps) {
    emitted += expect_same_leaf(s, op, {1, 1});
    emitted += expect_same_leaf(s, op, {0, 0});
    emitted += expect_same_leaf(s, op, {1, 0});
  }
  EXPECT_GT(emitted, 0u);
}

TEST(EdgeWindings, BoxesWithSharedFacesAndEdges) {
  std::size_t emitted = 0;
  // A tessellated box, a box sharing part of its top face plane and a box
  // touching it along an edge line only: coplanar overlaps and edges on
  // which more than two sheets meet.
  Scene s;
  add(s, test::tessellated_box({0, 0, 0}, {1, 1, 1}, 4), 1024);
  add(s, test::merge({test::box({0.25, 0.25, 0.5}, {0.75, 0.75, 1}), test::box({1, 1, 0}, {1.5, 1.5, 1})}), 1024);
  for (const Operation op : kOps) {
    emitted += expect_same_leaf(s, op, {0, 0});
    emitted += expect_same_leaf(s, op, {1, 1});
  }
  EXPECT_GT(emitted, 0u);
}

TEST(EdgeWindings, ThreeOperandsAndAnOpenSheet) {
  std::size_t emitted = 0;
  Scene s;
  add(s, test::icosphere({0, 0, 0}, 1, 2), 1000);
  add(s, test::tessellated_box({-0.3, -0.3, -0.3}, {1.2, 0.4, 0.5}, 3), 1000);
  add(s, test::icosphere({-0.4, 0.2, 0.1}, 0.8, 1), 1000);
  for (const Operation op : kOps) {
    emitted += expect_same_leaf(s, op, {0, 0, 0});
    emitted += expect_same_leaf(s, op, {1, 1, 1});
  }
  Scene open;
  add(open, test::icosphere({0, 0, 0}, 1, 2), 1000);
  // One face of a box: an open sheet through the sphere.
  Mesh sheet = test::tessellated_box({-1.5, -1.5, 0.1}, {1.5, 1.5, 0.1 + 1e-3}, 3);
  Mesh top;
  for (std::size_t f = 0; f < sheet.face_count(); ++f) {
    bool up = true;
    for (const std::uint32_t v : sheet.face(f)) up &= sheet.vertices[v].z > 0.1 + 5e-4;
    if (!up) continue;
    std::vector<std::uint32_t> ids;
    for (const std::uint32_t v : sheet.face(f)) ids.push_back(top.add_vertex(sheet.vertices[v]));
    top.add_face(ids);
  }
  add(open, top, 1000, false);
  for (const Operation op : kOps) emitted += expect_same_leaf(open, op, {0, 0});
  EXPECT_GT(emitted, 0u);
}

TEST(EdgeWindings, TwinSurfaces) {
  std::size_t emitted = 0;
  // Operands sharing surfaces: a sphere and its copy (every edge has a twin on
  // each side), the copy reversed, and a box sharing a tessellated face with
  // a larger one, with a third operand crossing both.
  const Mesh sphere = test::icosphere({0, 0, 0}, 1, 2);
  Scene same, reversed, boxes;
  add(same, sphere, 1000);
  add(same, sphere, 1000);
  add(same, test::icosphere({0.6, 0.2, 0.1}, 0.7, 1), 1000);
  add(reversed, sphere, 1000);
  add(reversed, test::reverse_orientation(sphere), 1000);
  add(boxes, test::tessellated_box({0, 0, 0}, {1, 1, 1}, 4), 1024);
  add(boxes, test::tessellated_box({0, 0, 0}, {1, 1, 0.5}, 4), 1024);
  add(boxes, test::icosphere({0.5, 0.5, 0.5}, 0.6, 1), 1024);
  // A box continuing another's top face plane beyond its edge (a sheet in
  // t's plane on the far side of the edge) and doubling part of its side.
  Scene step;
  add(step, test::tessellated_box({0, 0, 0}, {1, 1, 1}, 2), 1024);
  add(step, test::tessellated_box({1, 0, 0.5}, {2, 1, 1}, 2), 1024);
  for (const Operation op : kOps) {
    emitted += expect_same_leaf(step, op, {0, 0});
    emitted += expect_same_leaf(step, op, {1, 1});
    emitted += expect_same_leaf(same, op, {0, 0, 0});
    emitted += expect_same_leaf(same, op, {1, 1, 1});
    emitted += expect_same_leaf(reversed, op, {0, 0});
    emitted += expect_same_leaf(boxes, op, {0, 0, 0});
  }
  EXPECT_GT(emitted, 0u);
}

TEST(EdgeWindings, SliverFan) {
  std::size_t emitted = 0;
  // Long thin triangles side by side (a fan around a far apex on each face
  // of a prism) crossed by a box: the pile shape the sharing is for.
  Scene s;
  Mesh prism;
  constexpr int kStrips = 24;
  const double len = 40;
  for (int i = 0; i < kStrips; ++i) {
    const double a = 2 * M_PI * i / kStrips;
    prism.add_vertex({0, std::cos(a), std::sin(a)});
    prism.add_vertex({len, std::cos(a + 0.02), std::sin(a + 0.02)});
  }
  for (int i = 0; i < kStrips; ++i) {
    const auto p = static_cast<std::uint32_t>(2 * i), q = static_cast<std::uint32_t>(2 * ((i + 1) % kStrips));
    prism.add_face({p, q, q + 1});
    prism.add_face({p, q + 1, p + 1});
  }
  // Caps (fans around the first vertex of each ring).
  for (int i = 1; i + 1 < kStrips; ++i) {
    prism.add_face({0, static_cast<std::uint32_t>(2 * (i + 1)), static_cast<std::uint32_t>(2 * i)});
    prism.add_face({1, static_cast<std::uint32_t>(2 * i + 1), static_cast<std::uint32_t>(2 * (i + 1) + 1)});
  }
  add(s, prism, 256);
  add(s, test::box({10, -0.5, -2}, {20, 0.5, 2}), 256);
  for (const Operation op : kOps) {
    emitted += expect_same_leaf(s, op, {0, 0});
    emitted += expect_same_leaf(s, op, {1, 1});
  }
  EXPECT_GT(emitted, 0u);
}

TEST(EdgeWindings, NeighbourOrderReachesEachGroupThroughSharedEdges) {
  // Two spheres and a box, their triangles shuffled (so that soup order is
  // no walk over the surface): the order must visit every polygon of the
  // range once, and each polygon but the first of its group (the polygons
  // connected through shared input edges, found here by union-find) must
  // come after a polygon sharing an input edge with it. Groups start in soup
  // order of their first polygon.
  Scene s;
  add(s, test::uv_sphere({0, 0, 0}, 0.5, 12, 10), 512);
  add(s, test::uv_sphere({0.3, 0, 0}, 0.4, 9, 7), 512);
  add(s, test::box({2, 2, 2}, {3, 3, 3}), 512);
  std::mt19937 rng(5);
  std::vector<std::size_t> perm(s.tris.size());
  std::iota(perm.begin(), perm.end(), 0);
  std::shuffle(perm.begin(), perm.end(), rng);
  Soup soup;
  for (std::size_t i = 0; i < perm.size(); ++i)
    soup.push_back(unbuilt_triangle(s.tris[perm[i]], static_cast<std::uint32_t>(i), s.operand[perm[i]]));
  const auto key = [](const IntPoint& a, const IntPoint& b) {
    std::array<std::int64_t, 6> k{a.x, a.y, a.z, b.x, b.y, b.z};
    if (std::array<std::int64_t, 3>{b.x, b.y, b.z} < std::array<std::int64_t, 3>{a.x, a.y, a.z})
      k = {b.x, b.y, b.z, a.x, a.y, a.z};
    return k;
  };
  const auto share_edge = [&](std::size_t p, std::size_t q) {
    const auto &c = *soup[p].corners, &d = *soup[q].corners;
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j)
        if (key(c[i], c[(i + 1) % 3]) == key(d[j], d[(j + 1) % 3])) return true;
    return false;
  };
  for (const auto& [begin, end] : {std::pair<std::size_t, std::size_t>{0, soup.size()}, {7, soup.size() / 2}}) {
    const std::size_t n = end - begin;
    std::vector<std::size_t> group(n);
    std::iota(group.begin(), group.end(), 0);
    const auto find = [&](std::size_t x) {
      while (group[x] != x) x = group[x] = group[group[x]];
      return x;
    };
    for (std::size_t p = 0; p < n; ++p)
      for (std::size_t q = p + 1; q < n; ++q)
        if (share_edge(begin + p, begin + q)) group[std::max(find(p), find(q))] = std::min(find(p), find(q));
    const std::vector<std::uint32_t> order = edge_neighbour_order(soup, begin, end);
    ASSERT_EQ(order.size(), n);
    std::vector<char> seen(n, 0);
    std::size_t groups = 0, last_first = 0;
    for (std::size_t k = 0; k < n; ++k) {
      ASSERT_GE(order[k], begin);
      ASSERT_LT(order[k], end);
      const std::size_t p = order[k] - begin;
      ASSERT_FALSE(seen[p]) << "visited twice";
      seen[p] = 1;
      bool after_neighbour = false;
      for (std::size_t j = 0; j < k && !after_neighbour; ++j) after_neighbour = share_edge(order[j], order[k]);
      if (after_neighbour) continue;
      // First of its group: the group's smallest index, later than the previous group's.
      EXPECT_EQ(find(p), p) << "polygon " << p << " starts a group it is not the first of";
      EXPECT_TRUE(groups == 0 || p > last_first);
      last_first = p;
      ++groups;
    }
    std::size_t want_groups = 0;
    for (std::size_t p = 0; p < n; ++p) want_groups += find(p) == p;
    EXPECT_EQ(groups, want_groups);
    if (n == soup.size()) {
      EXPECT_EQ(groups, 3u);  // three closed surfaces (a random half of them falls apart)
    }
  }
}

}  // namespace
}  // namespace ember::core
