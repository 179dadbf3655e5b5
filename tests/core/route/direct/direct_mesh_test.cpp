// The solid path's direct route (src/core/direct_mesh.hpp): two solids that
// meet in general position get their triangle mesh straight from the
// intersection curve. run_checked compares every result with the
// subdivision's (volume, area) and checks it is closed; these tests pin down
// when the route is taken and the configurations its face walk must handle:
// curves from edge to edge, curves that close inside one triangle, nested
// closed curves, and the fallback for contacts that are not transversal.
#include <gtest/gtest.h>

#include "support/boolean_checks.hpp"

namespace ember::test {
namespace {

using Op = Operation;

constexpr Op kOps[] = {Op::Union, Op::Intersection, Op::Difference, Op::Xor};

BooleanResult run_direct(const std::vector<Mesh>& ops, Op op, int threads = 0) {
  BooleanOptions opt;
  opt.threads = threads;
  BooleanResult r = run_checked(ops, op, opt);
  EXPECT_TRUE(r.stats.diagnostic("solid_path") != 0);
  EXPECT_TRUE(r.stats.diagnostic("direct_mesh") != 0) << "the direct route declined";
  EXPECT_EQ(r.stats.diagnostic("fallback_regions"), 0u);
  return r;
}

TEST(DirectMesh, TakenWhenTwoSolidsMeetInGeneralPosition) {
  const std::vector<Mesh> ops =
      snapped({icosphere({0, 0, 0}, 1.0, 3), rotate(torus({0.4, 0.1, 0.0}, 0.9, 0.3, 40, 16), random_rotation(5))});
  for (const Op op : kOps) {
    const BooleanResult r = run_direct(ops, op);
    EXPECT_GT(r.stats.diagnostic("regions"), 0u);  // kept faces of cut triangles
    EXPECT_EQ(r.stats.diagnostic("tjunctions_resolved"), 0u);
  }
  // Polygon output and three operands take the solid path's pieces.
  BooleanOptions polygons;
  polygons.output = BooleanOptions::Output::Polygons;
  EXPECT_FALSE(boolean(ops, Op::Union, polygons).stats.diagnostic("direct_mesh") != 0);
  const std::vector<Mesh> three =
      snapped({icosphere({0, 0, 0}, 1.0, 2), icosphere({0.7, 0.1, 0.05}, 0.8, 2), icosphere({0.2, 0.6, -0.1}, 0.7, 2)});
  const BooleanResult r3 = run_checked(three, Op::Union);
  EXPECT_TRUE(r3.stats.diagnostic("solid_path") != 0);
  EXPECT_FALSE(r3.stats.diagnostic("direct_mesh") != 0);
}

TEST(DirectMesh, ACurveThatClosesInsideOneTriangle) {
  // A thin hexagonal prism pierces the box's top face well inside one of
  // its two triangles (at distance >= 0.49 from either diagonal): the
  // triangle meets the prism in a closed curve, its kept face has a hole
  // (union) or is the disc inside the curve (intersection).
  const std::vector<Mesh> ops = snapped({box({-2, -2, -2}, {2, 2, 2}), cylinder({1.0, -0.3, 1.0}, 0.1, 2.0, 6)});
  for (const Op op : kOps) run_direct(ops, op);
}

TEST(DirectMesh, NestedClosedCurvesAndTheSameMeshAtEveryThreadCount) {
  // A torus lying flat, its centre 0.013 above the top face: the face's
  // plane cuts its tube in two concentric curves inside one triangle. The
  // annulus between them is inside the torus; the disc inside the inner
  // curve and the rest of the triangle outside.
  const std::vector<Mesh> ops = snapped({box({-2, -2, -2}, {2, 2, 2}), torus({1.0, -0.3, 2.013}, 0.3, 0.1, 24, 12)});
  for (const Op op : kOps) {
    const BooleanResult one = run_direct(ops, op, 1);
    for (const int threads : {2, 4}) {
      const BooleanResult many = run_direct(ops, op, threads);
      EXPECT_EQ(many.mesh.vertices, one.mesh.vertices) << threads << " threads";
      EXPECT_EQ(many.mesh.indices, one.mesh.indices) << threads << " threads";
    }
  }
  // Two tori side by side and one inside the other's hole: several curves,
  // one of them inside another, in the same triangle.
  const std::vector<Mesh> rings =
      snapped({box({-2, -2, -2}, {2, 2, 2}),
               merge({torus({1.0, -0.3, 2.013}, 0.3, 0.08, 24, 12), torus({1.0, -0.3, 1.991}, 0.12, 0.04, 16, 10)})});
  for (const Op op : kOps) run_direct(rings, op);
}

TEST(DirectMesh, ContactsThatAreNotTransversalTakeThePieces) {
  // Coplanar top faces, and a corner resting on a face: the same exact
  // result through the solid path's pieces and the mesh stage.
  const std::vector<Mesh> coplanar = snapped({box({-2, -2, -2}, {2, 2, 2}), box({-1, -1, 1}, {1, 1, 2})});
  const std::vector<Mesh> corner = snapped(
      {box({-2, -2, -2}, {2, 2, 2}), tetrahedron({0.3, 0.2, 2.0}, {1.0, 0.1, 3.0}, {0.1, 1.0, 3.1}, {0.7, 0.8, 2.6})});
  for (const auto& ops : {coplanar, corner})
    for (const Op op : kOps) {
      const BooleanResult r = run_checked(ops, op);
      EXPECT_TRUE(r.stats.diagnostic("solid_path") != 0);
      EXPECT_FALSE(r.stats.diagnostic("direct_mesh") != 0);
    }
}

}  // namespace
}  // namespace ember::test
