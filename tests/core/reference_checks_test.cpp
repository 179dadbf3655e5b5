// Self-tests of the header-only test support code (shapes + reference checks).
// They do not call the Boolean core, so they validate the references used by
// the core tests on their own.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "support/mesh_checks.hpp"
#include "support/shapes.hpp"

namespace ember::test {
namespace {

const double kPi = std::numbers::pi;

TEST(SupportShapes, BoxesAreClosedOutwardAndExact) {
  Mesh t = box({0, 0, 0}, {2, 3, 5});
  Mesh q = box_quads({-1, -1, -1}, {1, 2, 3});
  EXPECT_EQ(t.face_count(), 12u);
  EXPECT_EQ(q.face_count(), 6u);
  EXPECT_TRUE(closed_oriented(t));
  EXPECT_TRUE(closed_oriented(q));
  EXPECT_EQ(volume(t), 30.0);
  EXPECT_EQ(volume(q), 24.0);
  EXPECT_EQ(surface_area(t), 2.0 * (6 + 10 + 15));
  EXPECT_EQ(face_problems(t, 0), "");
  EXPECT_EQ(face_problems(q, 0), "");
  Vec3l va = twice_vector_area(t);
  EXPECT_EQ(va.x, 0);
  EXPECT_EQ(va.y, 0);
  EXPECT_EQ(va.z, 0);
}

TEST(SupportChecks, TjunctionVerticesFindsAVertexInsideATwiceUsedEdge) {
  EXPECT_EQ(tjunction_vertices(box({0, 0, 0}, {1, 2, 3})), 0u);
  Mesh m;
  for (const Vec3d p : {Vec3d{0, 0, 0}, Vec3d{2, 0, 0}, Vec3d{0, 2, 0}, Vec3d{1, 0, 0}, Vec3d{0, 0, 2}, Vec3d{1, 0, 5},
                        Vec3d{2, 1, 5}, Vec3d{2, 0, 1}})
    m.add_vertex(p);
  m.add_face({0, 1, 2});
  m.add_face({1, 0, 4});  // edge {0, 1} used twice, vertex 3 = (1, 0, 0) in its middle
  m.add_face({3, 5, 6});
  EXPECT_EQ(tjunction_vertices(m), 1u);
  m.vertices[3] = {1, 0, 1e-300};  // off the line by a hair: no longer on the edge
  EXPECT_EQ(tjunction_vertices(m), 0u);
  m.vertices[3] = {1, 0, 0};
  m.add_face({0, 1, 7});  // a third use: non-manifold edge, not counted
  EXPECT_EQ(tjunction_vertices(m), 0u);
}

TEST(SupportShapes, BoxDiagonalsMatchOnSharedFaces) {
  // The +x face of [0,1]^3 and the -x face of [1,2]x[0,1]^2 use the same
  // diagonal, so the triangles coincide with opposite orientation.
  Mesh a = box({0, 0, 0}, {1, 1, 1}), b = box({1, 0, 0}, {2, 1, 1});
  Mesh m = merge({a, b});
  // Weld by coordinates and check the shared face cancels: every directed edge
  // on x = 1 has its reverse.
  MeshBuilder w;
  for (std::size_t f = 0; f < m.face_count(); ++f) {
    std::vector<Vec3d> pts;
    for (auto i : m.face(f)) pts.push_back(m.vertices[i]);
    w.face(pts);
  }
  Mesh welded = w.take();
  std::map<std::pair<std::uint32_t, std::uint32_t>, int> edges;
  for (std::size_t f = 0; f < welded.face_count(); ++f) {
    auto face = welded.face(f);
    for (std::size_t k = 0; k < 3; ++k) ++edges[{face[k], face[(k + 1) % 3]}];
  }
  for (const auto& [e, c] : edges) {
    auto it = edges.find(std::make_pair(e.second, e.first));
    ASSERT_NE(it, edges.end()) << "unmatched edge " << e.first << "->" << e.second;
    EXPECT_EQ(it->second, c);
  }
}

TEST(SupportShapes, TessellatedBoxHasManyCoplanarFaces) {
  Mesh m = tessellated_box({0, 0, 0}, {4, 4, 2}, 4);
  EXPECT_EQ(m.face_count(), 6u * 16 * 2);
  EXPECT_TRUE(closed_oriented(m));
  EXPECT_EQ(volume(m), 32.0);
  Mesh q = tessellated_box({0, 0, 0}, {3, 3, 3}, 3, false);
  EXPECT_TRUE(closed_oriented(q));
  EXPECT_EQ(volume(q), 27.0);
}

TEST(SupportShapes, CurvedShapesConvergeToAnalyticVolumes) {
  Mesh s = icosphere({1, 2, 3}, 2.0, 4);
  EXPECT_TRUE(closed_oriented(s));
  EXPECT_EQ(s.face_count(), 20u * 256);
  double vs = 4.0 / 3.0 * kPi * 8;
  EXPECT_LT(volume(s), vs);
  EXPECT_GT(volume(s), 0.99 * vs);
  EXPECT_GT(volume(icosphere({0, 0, 0}, 2.0, 4)), volume(icosphere({0, 0, 0}, 2.0, 2)));

  Mesh u = uv_sphere({0, 0, 0}, 1.0, 64, 32);
  EXPECT_TRUE(closed_oriented(u));
  EXPECT_NEAR(volume(u), 4.0 / 3.0 * kPi, 0.01 * 4.0 / 3.0 * kPi);

  Mesh t = torus({0, 0, 0}, 2.0, 0.5, 64, 32);
  EXPECT_TRUE(closed_oriented(t));
  EXPECT_NEAR(volume(t), 2 * kPi * kPi * 2.0 * 0.25, 0.01 * 2 * kPi * kPi * 2.0 * 0.25);
  EXPECT_NEAR(surface_area(t), 4 * kPi * kPi * 2.0 * 0.5, 0.01 * 4 * kPi * kPi);

  Mesh c = cylinder({0, 0, -1}, 1.0, 2.0, 128);
  EXPECT_TRUE(closed_oriented(c));
  EXPECT_NEAR(volume(c), 2 * kPi, 0.01 * 2 * kPi);
  EXPECT_EQ(face_problems(c, 1e-12), "");
}

TEST(SupportShapes, TetrahedronIsOutwardForEitherOrder) {
  Mesh a = tetrahedron({0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1});
  Mesh b = tetrahedron({0, 0, 0}, {0, 1, 0}, {1, 0, 0}, {0, 0, 1});
  EXPECT_TRUE(closed_oriented(a));
  EXPECT_TRUE(closed_oriented(b));
  EXPECT_DOUBLE_EQ(volume(a), 1.0 / 6);
  EXPECT_DOUBLE_EQ(volume(b), 1.0 / 6);
}

TEST(SupportTransforms, RandomRotationIsOrthonormalAndDeterministic) {
  for (std::uint64_t seed = 1; seed <= 20; ++seed) {
    Mat3 r = random_rotation(seed);
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) {
        double d = r[0][i] * r[0][j] + r[1][i] * r[1][j] + r[2][i] * r[2][j];
        EXPECT_NEAR(d, i == j ? 1.0 : 0.0, 1e-14);
      }
    double det = r[0][0] * (r[1][1] * r[2][2] - r[1][2] * r[2][1]) - r[0][1] * (r[1][0] * r[2][2] - r[1][2] * r[2][0]) +
                 r[0][2] * (r[1][0] * r[2][1] - r[1][1] * r[2][0]);
    EXPECT_NEAR(det, 1.0, 1e-14);
    EXPECT_EQ(random_rotation(seed), r);
  }
  EXPECT_NE(random_rotation(1), random_rotation(2));
}

TEST(SupportTransforms, TransformsActOnVolume) {
  Mesh b = box({0, 0, 0}, {1, 2, 3});
  EXPECT_EQ(volume(translate(b, {5, -3, 2})), 6.0);
  EXPECT_EQ(volume(scale(b, 2)), 48.0);
  EXPECT_NEAR(volume(rotate(b, random_rotation(7))), 6.0, 1e-13);
  EXPECT_EQ(volume(reverse_orientation(b)), -6.0);
  EXPECT_TRUE(closed_oriented(reverse_orientation(b)));
  Mesh m = merge({b, translate(b, {10, 0, 0})});
  EXPECT_EQ(m.face_count(), 24u);
  EXPECT_EQ(volume(m), 12.0);
}

TEST(SupportTransforms, SnapToGridIsDyadicAndCoarse) {
  std::vector<Mesh> ms{rotate(icosphere({0, 0, 0}, 1.0, 2), random_rotation(3)),
                       translate(icosphere({0, 0, 0}, 1.0, 2), {0.3, 0, 0})};
  double h = snap_step(max_abs_coordinate(ms));
  EXPECT_EQ(h, std::ldexp(1.0, 1 - 21));  // max |x| = 1.3 -> 2^1
  auto s = snapped(ms);
  for (const Mesh& m : s)
    for (const Vec3d& p : m.vertices) {
      EXPECT_EQ(std::fmod(p.x, h), 0.0);
      EXPECT_EQ(std::fmod(p.y, h), 0.0);
      EXPECT_EQ(std::fmod(p.z, h), 0.0);
    }
  EXPECT_NEAR(volume(s[0]), volume(ms[0]), 1e-5);
  // Integers are already on the grid.
  std::vector<Mesh> ints{box({0, 0, 0}, {3, 5, 7})};
  EXPECT_EQ(snapped(ints)[0], ints[0]);
}

TEST(SupportShapes, PaperConfigurations) {
  auto [xs, ys] = beams(5);
  EXPECT_EQ(volume(xs), 5.0 * 11);
  EXPECT_EQ(volume(ys), 5.0 * 11);
  EXPECT_TRUE(closed_oriented(xs));
  auto cubes = staircase_cubes(20);
  EXPECT_EQ(cubes.size(), 20u);
  for (const Mesh& c : cubes) EXPECT_EQ(volume(c), 20.0 * 20 * 4);
  auto rc = rotated_cubes(20, 1.0);
  for (const Mesh& c : rc) EXPECT_NEAR(volume(c), 4.0, 1e-13);
  EXPECT_EQ(volume(nested_shells({0, 0, 0}, {4, 4, 4}, {1, 1, 1}, {2, 2, 2})), 65.0);
}

TEST(SupportWinding, WindingNumbersOfSimpleConfigurations) {
  Mesh b = box({0, 0, 0}, {2, 2, 2});
  EXPECT_NEAR(winding_number(b, {1, 1, 1}), 1.0, 1e-12);
  EXPECT_NEAR(winding_number(b, {3, 1, 1}), 0.0, 1e-12);
  EXPECT_NEAR(winding_number(reverse_orientation(b), {1, 1, 1}), -1.0, 1e-12);
  Mesh n = nested_shells({0, 0, 0}, {4, 4, 4}, {1, 1, 1}, {2, 2, 2});
  EXPECT_NEAR(winding_number(n, {1.5, 1.5, 1.5}), 2.0, 1e-12);
  EXPECT_NEAR(winding_number(n, {3, 3, 3}), 1.0, 1e-12);
  Mesh si = self_intersecting_pair({0, 0, 0}, {2, 2, 2}, {1, 1, 1}, {3, 3, 3});
  EXPECT_NEAR(winding_number(si, {1.5, 1.5, 1.5}), 2.0, 1e-12);
  EXPECT_NEAR(winding_number(si, {2.5, 2.5, 2.5}), 1.0, 1e-12);
  Mesh t = torus({0, 0, 0}, 2, 0.5, 32, 16);
  EXPECT_NEAR(winding_number(t, {2, 0, 0}), 1.0, 1e-9);
  EXPECT_NEAR(winding_number(t, {0, 0, 0}), 0.0, 1e-9);
  // A T-junction soup: a 2x1x1 box whose +y face is split at x = 1 while the
  // other faces are not; still winding number 1 inside.
  Mesh tj;
  for (Vec3d p : {Vec3d{0, 0, 0},
                  {2, 0, 0},
                  {0, 1, 0},
                  {2, 1, 0},
                  {0, 0, 1},
                  {2, 0, 1},
                  {0, 1, 1},
                  {2, 1, 1},
                  {1, 1, 0},
                  {1, 1, 1}})
    tj.add_vertex(p);
  tj.add_face({0, 4, 6, 2});  // -x
  tj.add_face({1, 3, 7, 5});  // +x
  tj.add_face({0, 1, 5, 4});  // -y
  tj.add_face({2, 6, 9, 8});  // +y, left half
  tj.add_face({8, 9, 7, 3});  // +y, right half
  tj.add_face({0, 2, 3, 1});  // -z
  tj.add_face({4, 5, 7, 6});  // +z
  EXPECT_NEAR(winding_number(tj, {0.5, 0.5, 0.5}), 1.0, 1e-12);
  EXPECT_NEAR(winding_number(tj, {1.5, 0.5, 0.5}), 1.0, 1e-12);
  EXPECT_EQ(volume(tj), 2.0);
}

TEST(SupportChecks, PointTriangleDistance) {
  Vec3d a{0, 0, 0}, b{1, 0, 0}, c{0, 1, 0};
  EXPECT_DOUBLE_EQ(point_triangle_distance({0.2, 0.2, 3}, a, b, c), 3.0);
  EXPECT_DOUBLE_EQ(point_triangle_distance({-1, -1, 0}, a, b, c), std::sqrt(2.0));
  EXPECT_DOUBLE_EQ(point_triangle_distance({2, 0, 0}, a, b, c), 1.0);
  EXPECT_DOUBLE_EQ(point_triangle_distance({1, 1, 0}, a, b, c), std::sqrt(0.5));
  EXPECT_DOUBLE_EQ(point_triangle_distance({0.5, -2, 0}, a, b, c), 2.0);
  EXPECT_DOUBLE_EQ(distance_to_surface(box({0, 0, 0}, {2, 2, 2}), {1, 1, 1.25}), 0.75);
}

TEST(SupportChecks, FaceProblemsAreDetected) {
  Mesh m;
  m.add_vertex({0, 0, 0}), m.add_vertex({1, 0, 0}), m.add_vertex({2, 0, 0}), m.add_vertex({1, 1, 0});
  m.add_face({0, 1});
  EXPECT_NE(face_problems(m), "");
  Mesh z;
  z.vertices = m.vertices;
  z.add_face({0, 1, 2});  // collinear: zero area
  EXPECT_NE(face_problems(z), "");
  Mesh nc;
  nc.add_vertex({0, 0, 0}), nc.add_vertex({2, 0, 0}), nc.add_vertex({1, 0.5, 0}), nc.add_vertex({2, 2, 0}),
      nc.add_vertex({0, 2, 0});
  nc.add_face({0, 1, 2, 3, 4});  // reflex vertex at index 2
  EXPECT_EQ(face_problems(nc), "");
  EXPECT_NE(face_problems(nc, 0), "");
  Mesh bad;
  bad.vertices = m.vertices;
  bad.add_face({0, 1, 7});
  EXPECT_NE(face_problems(bad), "");
  EXPECT_EQ(face_problems(Mesh{}), "");
}

TEST(SupportChecks, ReferenceIndicatorSemantics) {
  auto call = [](const Indicator& f, std::vector<int> w) { return f(WindingVector(w.data(), w.size())); };
  auto u = reference_indicator(Operation::Union, 2);
  EXPECT_TRUE(call(u, {1, 0}));
  EXPECT_TRUE(call(u, {0, -1}));
  EXPECT_FALSE(call(u, {0, 0}));
  auto i = reference_indicator(Operation::Intersection, 3);
  EXPECT_TRUE(call(i, {1, 2, 1}));
  EXPECT_FALSE(call(i, {1, 0, 1}));
  auto d = reference_indicator(Operation::Difference, 3);
  EXPECT_TRUE(call(d, {1, 0, 0}));
  EXPECT_FALSE(call(d, {1, 0, 1}));
  EXPECT_FALSE(call(d, {0, 0, 0}));
  auto x = reference_indicator(Operation::Xor, 3);
  EXPECT_TRUE(call(x, {1, 1, 1}));
  EXPECT_FALSE(call(x, {1, 0, 2}));
  auto k = reference_indicator(Operation::AtLeastK, 4, 2);
  EXPECT_TRUE(call(k, {0, 1, 0, 1}));
  EXPECT_FALSE(call(k, {0, 1, 0, 0}));
}

TEST(SupportChecks, MembershipCheckAcceptsCorrectAndRejectsWrongResults) {
  Mesh a = box({0, 0, 0}, {2, 2, 2}), b = box({1, 1, 1}, {3, 3, 3});
  std::vector<Mesh> ops{a, b};
  // Hand-made correct intersection and a wrong one.
  Mesh inter = box({1, 1, 1}, {2, 2, 2});
  auto good = membership_check(ops, Operation::Intersection, inter, 300, 42);
  EXPECT_EQ(good.checked, 300);
  EXPECT_EQ(good.mismatches, 0) << good.first;
  EXPECT_EQ(good.non_integer, 0);
  auto wrong = membership_check(ops, Operation::Union, inter, 300, 42);
  EXPECT_EQ(wrong.checked, 300);
  EXPECT_GT(wrong.mismatches, 0);
  EXPECT_NE(wrong.first, "");
  // Disjoint union: the merged operands are the exact result.
  std::vector<Mesh> disjoint{a, translate(a, {5, 0, 0})};
  auto u = membership_check(disjoint, Operation::Union, merge(disjoint), 300, 43);
  EXPECT_EQ(u.mismatches, 0) << u.first;
  // An inverted output (winding -1 inside) is rejected.
  auto inv = membership_check(ops, Operation::Intersection, reverse_orientation(inter), 300, 44);
  EXPECT_GT(inv.mismatches, 0);
}

TEST(SupportChecks, VoxelVolumeIsExact) {
  std::vector<std::vector<Box>> ops{{{{0, 0, 0}, {2, 2, 2}}}, {{{1, 1, 1}, {3, 3, 3}}}};
  EXPECT_EQ(voxel_volume(ops, reference_indicator(Operation::Union, 2)), 15.0);
  EXPECT_EQ(voxel_volume(ops, reference_indicator(Operation::Intersection, 2)), 1.0);
  EXPECT_EQ(voxel_volume(ops, reference_indicator(Operation::Difference, 2)), 7.0);
  EXPECT_EQ(voxel_volume(ops, reference_indicator(Operation::Xor, 2)), 14.0);
  std::vector<std::vector<Box>> half{{{{0, 0, 0}, {1.5, 1, 1}}}, {{{0.5, 0, 0}, {2, 1, 1}}}};
  EXPECT_EQ(voxel_volume(half, reference_indicator(Operation::Intersection, 2), 0.5), 1.0);
  auto meshes = box_meshes(ops);
  EXPECT_EQ(meshes.size(), 2u);
  EXPECT_EQ(volume(meshes[0]), 8.0);
}

}  // namespace
}  // namespace ember::test
