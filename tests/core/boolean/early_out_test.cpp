// The early terminations of Section 4.5 (indicator reachability, solid-operand
// shortcuts) and thread-count independence must never change a result: the
// same Boolean with and without them has the same volume, and every thread
// count gives bit-identical output.
#include <gtest/gtest.h>

#include "support/boolean_checks.hpp"

namespace ember::test {
namespace {

using Op = Operation;

std::vector<Mesh> curved_pair() {
  return snapped({icosphere({0, 0, 0}, 1.0, 3), rotate(torus({0.4, 0.1, 0.0}, 0.9, 0.3, 40, 16), random_rotation(5))});
}

TEST(EarlyOut, SolidFlagGivesSameVolumesAsGeneralPath) {
  const std::vector<Mesh> ops = curved_pair();
  BooleanOptions solid;
  solid.all_solid = true;
  BooleanOptions no_proof;  // the general path: no promise, no solid proof
  no_proof.detect_solid = false;
  for (Op op : {Op::Union, Op::Intersection, Op::Difference, Op::Xor}) {
    const BooleanResult general = run_checked(ops, op, no_proof);
    const BooleanResult fast = run_checked(ops, op, solid);
    EXPECT_TRUE(close_rel(volume(general.mesh), volume(fast.mesh), 1e-12)) << int(op);
    EXPECT_TRUE(close_rel(surface_area(general.mesh), surface_area(fast.mesh), 1e-12)) << int(op);
    const MembershipReport m = membership_check(ops, op, fast.mesh, 200, 7);
    EXPECT_EQ(m.mismatches, 0) << int(op);
  }
}

TEST(EarlyOut, TrianglesTheSubdivisionCutComeBackWhole) {
  // A sphere well inside a finely tessellated box: nothing meets, so the
  // union is the box's triangles and the intersection the sphere's. The
  // subdivision still cuts the triangles its planes cross; every piece
  // reaches the output uncut, so each such triangle is emitted whole again
  // (even as raw polygons, where nothing else would join the pieces).
  // (The solid path has no subdivision: forced here. The solid path gives
  // the same on its own: no triangle is touched.)
  const std::vector<Mesh> ops =
      snapped({tessellated_box({-1, -1, -1}, {1, 1, 1}, 12), icosphere({0.1, -0.05, 0.02}, 0.5, 3)});
  BooleanOptions polygons;
  polygons.output = BooleanOptions::Output::Polygons;
  polygons.route = BooleanOptions::Route::General;
  const BooleanResult uni = run_checked(ops, Op::Union, polygons);
  EXPECT_GT(uni.stats.diagnostic("merged_triangles"), 0u) << "the subdivision should have cut some box triangles";
  EXPECT_EQ(uni.mesh.face_count(), ops[0].face_count());
  const BooleanResult inter = run_checked(ops, Op::Intersection, polygons);
  EXPECT_EQ(inter.mesh.face_count(), ops[1].face_count());
  BooleanOptions subdivided;
  subdivided.route = BooleanOptions::Route::General;
  const BooleanResult mesh = run_checked(ops, Op::Union, subdivided);
  EXPECT_EQ(mesh.stats.diagnostic("merged_triangles"), uni.stats.diagnostic("merged_triangles"));
  EXPECT_TRUE(close_rel(volume(mesh.mesh), volume(ops[0]), 1e-12));
  polygons.route = BooleanOptions::Route::Automatic;
  const BooleanResult direct = run_checked(ops, Op::Union, polygons);
  EXPECT_TRUE(direct.stats.diagnostic("solid_path") != 0);
  EXPECT_EQ(direct.mesh.face_count(), ops[0].face_count());
  EXPECT_EQ(direct.stats.diagnostic("merged_triangles"), 0u);
}

TEST(EarlyOut, PerOperandSolidFlags) {
  const std::vector<Mesh> ops = curved_pair();
  BooleanOptions first_only;
  first_only.solid = {true, false};
  const BooleanResult a = run_checked(ops, Op::Difference);
  const BooleanResult b = run_checked(ops, Op::Difference, first_only);
  EXPECT_TRUE(close_rel(volume(a.mesh), volume(b.mesh), 1e-12));
  BooleanOptions wrong_size;
  wrong_size.solid = {true};
  EXPECT_THROW(boolean(ops, Op::Union, wrong_size), Error);
}

TEST(EarlyOut, CustomIndicatorWithoutPruningMatchesBuiltIn) {
  // Custom indicators get no reachability pruning: the same result must come
  // out of the full computation.
  const std::vector<Mesh> ops = curved_pair();
  const BooleanResult builtin = run_checked(ops, Op::Difference);
  const BooleanResult custom =
      run_checked(ops, Op::Union, with_indicator([](WindingVector w) { return w[0] != 0 && w[1] == 0; }));
  EXPECT_TRUE(close_rel(volume(builtin.mesh), volume(custom.mesh), 1e-12));
}

TEST(EarlyOut, NaryMillingSubtractionPrunesAndStaysExact) {
  // W - T1 - ... - T6 with boxes: exact volume against voxel counting, with
  // and without the solid flag.
  std::vector<std::vector<Box>> boxes{{{{0, 0, 0}, {12, 12, 4}}}};
  for (int i = 0; i < 6; ++i) boxes.push_back({{{1.0 + 2 * i, 1, 2}, {2.0 + 2 * i, 11, 5}}});
  const std::vector<Mesh> ops = box_meshes(boxes);
  const double expected = voxel_volume(boxes, reference_indicator(Op::Difference, ops.size()));
  EXPECT_EQ(volume(run_checked(ops, Op::Difference).mesh), expected);
  BooleanOptions solid;
  solid.all_solid = true;
  EXPECT_EQ(volume(run_checked(ops, Op::Difference, solid).mesh), expected);
}

TEST(EarlyOut, ThreadCountsGiveBitIdenticalResults) {
  const std::vector<Mesh> ops = curved_pair();
  for (int mode : {0, 1, 2}) {  // general path, solid proof (default), solid promise
    BooleanOptions o;
    o.detect_solid = mode == 1;
    o.all_solid = mode == 2;
    o.threads = 1;
    const BooleanResult one = boolean(ops, Op::Union, o);
    for (int t : {2, 8}) {
      o.threads = t;
      const BooleanResult many = boolean(ops, Op::Union, o);
      EXPECT_EQ(one.mesh, many.mesh) << t << " threads, mode " << mode;
      ASSERT_EQ(one.provenance.size(), many.provenance.size());
      for (std::size_t i = 0; i < one.provenance.size(); ++i) {
        EXPECT_EQ(one.provenance[i].operand, many.provenance[i].operand);
        EXPECT_EQ(one.provenance[i].face, many.provenance[i].face);
      }
    }
  }
}

}  // namespace
}  // namespace ember::test
