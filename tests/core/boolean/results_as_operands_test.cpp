// Results feed straight back: the default triangle output of a
// Boolean is closed, so it is a valid operand again with default options and
// is proven solid; a chain of Booleans agrees with the one-pass n-ary
// Boolean. The milling chain is the paper's motivating iterated-CSG use.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "support/boolean_checks.hpp"
#include "ember/io/mesh_io.hpp"

namespace ember::test {
namespace {

/// A ball tool of the milling sequence: a small sphere on a helical path that
/// dips into the top of the workpiece.
Mesh ball_tool(int step) {
  const double a = 0.45 * step;
  return uv_sphere({0.5 + 0.3 * std::cos(a), 0.5 + 0.3 * std::sin(a), 1.0 - 0.004 * step}, 0.12, 16, 8);
}

/// A square end mill on a grid-aligned path: every coordinate is a multiple of
/// 1/64, so every vertex of every result is a grid point and survives rounding
/// and re-quantization exactly.
Mesh square_tool(int step) {
  const double x = 0.125 + 0.09375 * (step % 8), y = 0.125 + 0.15625 * (step / 8);
  const double depth = 0.125 + 0.015625 * (step % 5);
  return box({x, y, 1.0 - depth}, {x + 0.1875, y + 0.1875, 1.5});
}

/// Written by ember and read back: what a user chaining CLI calls gets.
Mesh round_trip(const Mesh& m, MeshFormat format) { return read_mesh(write_mesh(m, format), format, "round trip"); }

TEST(Chaining, ResultsAreProvenSolidAndFeedBackWithDefaultOptions) {
  const Mesh a = box({0, 0, 0}, {1, 1, 1});
  const Mesh b = uv_sphere({1, 1, 1}, 0.6, 24, 12);
  const Mesh c = cylinder({0.3, 0.3, -0.5}, 0.2, 2.0, 20);
  const BooleanResult ab = run_checked({a, b}, Operation::Union);
  ASSERT_EQ(unbalanced_edges(ab.mesh), 0u);
  const Mesh ab_read = round_trip(ab.mesh, MeshFormat::Obj);
  const BooleanResult abc = run_checked({ab_read, c}, Operation::Difference);  // default options: no --allow-open
  EXPECT_EQ(abc.stats.solid_operands, 2u) << "ember's own result must pass the exact solid proof";
  EXPECT_EQ(unbalanced_edges(abc.mesh), 0u);
  // The chain agrees with the one-pass expression (a | b) - c.
  const std::vector<Mesh> ops{a, b, c};
  const Indicator chain = [](WindingVector w) { return (w[0] != 0 || w[1] != 0) && w[2] == 0; };
  const MembershipReport rep = membership_check(ops, chain, abc.mesh, 300, 11);
  EXPECT_EQ(rep.mismatches, 0) << rep.first;
  EXPECT_GT(rep.checked, 200);
}

/// Runs `steps` milling steps, each step's output (written as PLY and read
/// back) being the next input with default options; every result must be
/// closed and the chain must agree with the one-pass n-ary difference.
/// Returns how many steps found the previous result proven solid.
template <typename Tool>
int mill(int steps, Tool tool, double volume_tol) {
  const Mesh workpiece = box({0, 0, 0}, {1, 1, 1});
  std::vector<Mesh> ops{workpiece};
  Mesh current = workpiece;
  int proven = 0;
  for (int step = 0; step < steps; ++step) {
    const Mesh t = tool(step);
    ops.push_back(t);
    const BooleanResult r = run_checked({current, t}, Operation::Difference);
    EXPECT_EQ(unbalanced_edges(r.mesh), 0u) << "step " << step;
    EXPECT_GE(r.stats.solid_operands, 1u) << "step " << step << ": the tool is solid";
    proven += r.stats.solid_operands == 2;
    current = round_trip(r.mesh, MeshFormat::Ply);
  }
  const BooleanResult one_pass = run_checked(std::span<const Mesh>(ops), Operation::Difference);
  EXPECT_TRUE(close_rel(volume(current), volume(one_pass.mesh), volume_tol, 1e-12))
      << volume(current) << " vs one pass " << volume(one_pass.mesh);
  const MembershipReport rep = membership_check(ops, Operation::Difference, current, 300, 5);
  EXPECT_EQ(rep.mismatches, 0) << rep.first;
  EXPECT_GT(rep.checked, 200);
  return proven;
}

TEST(Chaining, ThirtyStepGridMillingIsProvenSolidAtEveryStep) {
  // Grid-aligned tools: results are exact after rounding, so each one is
  // proven solid again and the chain equals the one-pass difference exactly.
  EXPECT_EQ(mill(30, square_tool, 1e-12), 30);
}

// Ball tools: where two cavities meet, the exact result has sliver faces far
// thinner than the 2^-24 grid step of a unit workpiece. Re-quantizing the
// rounded result can flip them; the solid proof then rejects the operand and
// the general path (exact for any input) takes over: still closed, still
// right, slower. Past about 13 steps the general path on such re-quantized
// slivers fragments the output, so 12 steps here.
TEST(Chaining, BallMillingStaysClosedAndRightWhenRoundingBreaksTheProof) {
  const int proven = mill(12, ball_tool, 1e-6);
  RecordProperty("steps_with_previous_result_proven_solid", proven);
  EXPECT_GE(proven, 2) << "the first results (no cavities meeting yet) must be proven solid";
}

TEST(Chaining, SelfUnionReturnsTheInputsTriangles) {
  // A u A: the coplanar pieces of every face merge back; the count is A's.
  for (const Mesh& m : {uv_sphere({0, 0, 0}, 1, 24, 12), box({0, 0, 0}, {2, 1, 1}), torus({0, 0, 0}, 1, 0.3, 24, 12)}) {
    const BooleanResult r = run_checked({m, m}, Operation::Union);
    EXPECT_EQ(r.mesh.face_count(), m.triangle_count());
    EXPECT_TRUE(close_rel(volume(r.mesh), volume(m), 1e-6, 1e-12));  // inputs are rounded onto the grid once
  }
}

TEST(Chaining, CoplanarPileOfShiftedCubesBecomesOneBox) {
  // 100 unit cubes shifted by 0.01 along x (one operand each): the exact union
  // is the box [0, 1.99] x [0, 1]^2, i.e. 12 triangles. (tests/core/piles_test.cpp
  // has the larger piles.)
  std::vector<Mesh> cubes;
  for (int i = 0; i < 100; ++i) cubes.push_back(box({0.01 * i, 0, 0}, {0.01 * i + 1, 1, 1}));
  const BooleanResult r = run_checked(std::span<const Mesh>(cubes), Operation::Union);
  EXPECT_LE(r.mesh.face_count(), 12u);
  EXPECT_EQ(unbalanced_edges(r.mesh), 0u);
  EXPECT_TRUE(close_rel(volume(r.mesh), 1.99, 1e-7, 1e-12)) << volume(r.mesh);  // 0.01 i is rounded to the grid
}

TEST(Chaining, PolygonsOptionKeepsTheRawPieces) {
  const Mesh a = box({0, 0, 0}, {1, 1, 1}), b = box({0.5, 0.5, 0.5}, {1.5, 1.5, 1.5});
  BooleanOptions raw;
  raw.output = BooleanOptions::Output::Polygons;
  const BooleanResult p = run_checked({a, b}, Operation::Union, raw);
  const BooleanResult t = run_checked({a, b}, Operation::Union);
  EXPECT_TRUE(close_rel(volume(p.mesh), volume(t.mesh), 1e-12, 1e-12));
  bool any_polygon = false;
  for (std::size_t f = 0; f < p.mesh.face_count(); ++f) any_polygon = any_polygon || p.mesh.face_size(f) > 3;
  EXPECT_TRUE(any_polygon) << "raw output keeps the core's convex pieces";
  // The exact union of two overlapping cubes has 20 vertices and 36 triangles
  // once coplanar pieces merge and seam vertices go.
  EXPECT_EQ(t.mesh.vertices.size(), 20u);
  EXPECT_EQ(t.mesh.face_count(), 36u);
}

}  // namespace
}  // namespace ember::test
