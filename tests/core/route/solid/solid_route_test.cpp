// The solid path (src/core/solid_path.hpp): operands that are all solid are
// solved without the subdivision. Every core test compares it with the
// subdivision through run_checked (same volume and area); these tests pin
// down when it runs and the cases its shortcuts rest on: untouched
// components classified by one trace, pieces handed winding numbers across
// input edges, coplanar overlaps, touching without crossing, many operands.
#include <gtest/gtest.h>

#include "support/boolean_checks.hpp"

namespace ember::test {
namespace {

using Op = Operation;

TEST(SolidPath, RunsExactlyWhenEveryOperandIsSolid) {
  const std::vector<Mesh> ops =
      snapped({icosphere({0, 0, 0}, 1.0, 3), rotate(torus({0.4, 0.1, 0.0}, 0.9, 0.3, 40, 16), random_rotation(5))});
  EXPECT_TRUE(run_checked(ops, Op::Union).stats.diagnostic("solid_path") != 0);
  BooleanOptions off;
  off.route = BooleanOptions::Route::General;
  EXPECT_FALSE(run_checked(ops, Op::Union, off).stats.diagnostic("solid_path") != 0);
  BooleanOptions general;  // no proof, no promise: nothing is solid
  general.detect_solid = false;
  EXPECT_FALSE(run_checked(ops, Op::Union, general).stats.diagnostic("solid_path") != 0);
  // One operand not solid (two overlapping balls): the subdivision solves.
  const std::vector<Mesh> mixed = snapped(
      {merge({icosphere({0, 0, 0}, 1.0, 2), icosphere({0.5, 0, 0}, 1.0, 2)}), box({-0.2, -0.2, -2}, {0.3, 0.3, 2})});
  const BooleanResult r = run_checked(mixed, Op::Union);
  EXPECT_EQ(r.stats.solid_operands, 1u);
  EXPECT_FALSE(r.stats.diagnostic("solid_path") != 0);
}

TEST(SolidPath, AFaceUnderManySliversIsCutInParallelAndClassifiedAcrossItsCuts) {
  // 150 thin slabs stand on the top face of a box: each of the face's two
  // triangles is cut by ~300 partner planes into more pieces than the
  // solid path cuts one by one (its parallel cut), and its pieces take
  // their winding numbers from each other across the cut lines
  // (CutHandover::spread with its index of cut edges).
  // Same surface as the subdivision (run_checked), the same mesh at every
  // thread count.
  std::vector<Mesh> slabs;
  for (int k = 0; k < 150; ++k) {
    const double x = -1.5 + 3.0 * k / 150;
    slabs.push_back(box({x, -1.5, 1.5}, {x + 0.004, 1.5, 2.5}));
  }
  const std::vector<Mesh> ops = snapped({box({-2, -2, -2}, {2, 2, 2}), merge(slabs)});
  for (const Op op : {Op::Union, Op::Difference}) {
    BooleanOptions one;
    one.threads = 1;
    const BooleanResult r = run_checked(ops, op, one);
    EXPECT_TRUE(r.stats.diagnostic("solid_path") != 0);
    EXPECT_GT(r.mesh.face_count(), 600u);  // the top face in ~300 strips per triangle
    for (const int threads : {2, 4}) {
      BooleanOptions many;
      many.threads = threads;
      const BooleanResult m = boolean(ops, op, many);
      EXPECT_EQ(m.mesh.vertices, r.mesh.vertices) << threads << " threads";
      EXPECT_EQ(m.mesh.indices, r.mesh.indices) << threads << " threads";
    }
  }
}

TEST(SolidPath, UntouchedComponentsAreClassifiedWhole) {
  // Operand 0: a ball inside a large box, a ball outside it, and a ball
  // crossing its surface; operand 1: the box. Each ball far from the box's
  // surface is one untouched component, in or out as a whole.
  const std::vector<Mesh> parts = snapped({icosphere({0, 0, 0}, 0.5, 2), icosphere({4, 0, 0}, 0.5, 2),
                                           icosphere({2, 0, 0}, 0.5, 2), box({-2, -2, -2}, {2, 2, 2})});
  const std::vector<Mesh> ops{merge({parts[0], parts[1], parts[2]}), parts[3]};
  const double inner = volume(parts[0]), outer = volume(parts[1]), crossing = volume(parts[2]);
  const BooleanResult inter = run_checked(ops, Op::Intersection);
  const BooleanResult diff = run_checked(ops, Op::Difference);
  const BooleanResult uni = run_checked(ops, Op::Union);
  EXPECT_TRUE(inter.stats.diagnostic("solid_path") != 0);
  // The inner ball and part of the crossing one are inside, the rest outside.
  EXPECT_GT(volume(inter.mesh), inner + 0.3 * crossing);
  EXPECT_LT(volume(inter.mesh), inner + 0.7 * crossing);
  EXPECT_TRUE(close_rel(volume(inter.mesh) + volume(diff.mesh), inner + outer + crossing, 1e-9));
  EXPECT_TRUE(close_rel(volume(uni.mesh), 64 + volume(diff.mesh), 1e-9));
  EXPECT_EQ(membership_check(ops, Op::Intersection, inter.mesh, 300, 3).mismatches, 0);
}

TEST(SolidPath, CoplanarAndTouchingOperands) {
  // The same box twice (every face coplanar), boxes sharing a face, boxes
  // touching along an edge only, and a box resting on another's face.
  const Mesh a = box({0, 0, 0}, {2, 2, 2});
  struct Case {
    Mesh b;
    double union_volume, intersection_volume;
  };
  const Case cases[] = {{box({0, 0, 0}, {2, 2, 2}), 8, 8},
                        {box({2, 0, 0}, {4, 2, 2}), 16, 0},
                        {box({2, 2, 0}, {3, 3, 2}), 10, 0},
                        {box({0.5, 0.5, 2}, {1.5, 1.5, 3}), 9, 0},
                        {box({1, 1, 1}, {3, 3, 3}), 15, 1}};
  for (const Case& c : cases) {
    const std::vector<Mesh> ops = snapped({a, c.b});
    const BooleanResult u = run_checked(ops, Op::Union);
    EXPECT_TRUE(u.stats.diagnostic("solid_path") != 0);
    EXPECT_TRUE(close_rel(volume(u.mesh), c.union_volume, 1e-12, 1e-12)) << volume(u.mesh);
    const BooleanResult i = run_checked(ops, Op::Intersection);
    EXPECT_TRUE(close_rel(volume(i.mesh), c.intersection_volume, 1e-12, 1e-12)) << volume(i.mesh);
  }
}

TEST(SolidPath, ManyOperandsAndAtLeastK) {
  // Twelve balls on a ring, each overlapping its two neighbours: union,
  // intersection (empty), at least 2 (the lenses), xor.
  std::vector<Mesh> balls;
  for (int i = 0; i < 12; ++i) {
    const double a = 2 * std::numbers::pi * i / 12;
    balls.push_back(icosphere({3 * std::cos(a), 3 * std::sin(a), 0.1 * i}, 1.0, 2));
  }
  const std::vector<Mesh> ops = snapped(balls);
  for (const Op op : {Op::Union, Op::Intersection, Op::Xor}) {
    const BooleanResult r = run_checked(ops, op);
    EXPECT_TRUE(r.stats.diagnostic("solid_path") != 0) << int(op);
    EXPECT_EQ(membership_check(ops, op, r.mesh, 300, 11).mismatches, 0) << int(op);
  }
  const BooleanResult lenses = run_checked(ops, Op::AtLeastK, with_min_k(2));
  EXPECT_TRUE(lenses.stats.diagnostic("solid_path") != 0);
  EXPECT_EQ(membership_check(ops, Op::AtLeastK, lenses.mesh, 300, 13, 2).mismatches, 0);
}

TEST(SolidPath, StartedBeforeTheProofItIsTheSameBooleanAtEveryThreadCount) {
  // At more than one thread the solid path starts alongside the proof
  // (boolean.cpp); a failed proof abandons it. Operands that cross the other
  // one and are closed but not solid (self-intersecting, inverted, nested
  // shells) take the general path at every thread count; solid ones the
  // solid path. The meshes and warnings do not depend on the count.
  const Mesh cutter = box({0.5, 0.5, 0.5}, {2.5, 1.5, 1.5});
  const std::vector<std::pair<Mesh, bool>> cases{
      {box({0, 0, 0}, {2, 2, 2}), true},
      {self_intersecting_pair({0, 0, 0}, {2, 2, 2}, {1, 1, 1}, {3, 3, 3}), false},
      {reverse_orientation(box({0, 0, 0}, {2, 2, 2})), false},
      {nested_shells({0, 0, 0}, {4, 4, 4}, {1, 1, 1}, {2, 2, 2}), false}};
  for (std::size_t c = 0; c < cases.size(); ++c) {
    const std::vector<Mesh> ops = snapped({cases[c].first, cutter});
    for (const Op op : {Op::Union, Op::Difference}) {
      BooleanOptions one;
      one.threads = 1;
      const BooleanResult r = boolean(ops, op, one);
      EXPECT_EQ(r.stats.diagnostic("solid_path") != 0, cases[c].second) << c;
      EXPECT_GT(r.mesh.face_count(), 0u) << c;
      for (const int threads : {2, 4}) {
        BooleanOptions many;
        many.threads = threads;
        const BooleanResult m = boolean(ops, op, many);
        EXPECT_EQ(m.stats.diagnostic("solid_path"), r.stats.diagnostic("solid_path"))
            << c << ", " << threads << " threads";
        EXPECT_EQ(m.mesh.vertices, r.mesh.vertices) << c << ", " << threads << " threads";
        EXPECT_EQ(m.mesh.indices, r.mesh.indices) << c << ", " << threads << " threads";
        EXPECT_EQ(m.warnings, r.warnings) << c << ", " << threads << " threads";
      }
    }
  }
}

}  // namespace
}  // namespace ember::test
