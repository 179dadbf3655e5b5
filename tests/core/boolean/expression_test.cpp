// CSG expressions evaluated as one Boolean (ember/csg.hpp), checked
// independently of the library: winding numbers at sample points, volume
// identities between expressions and operations, the built-in operations'
// own bytes, and bit-identical output at 1 and 2 threads, on every route
// (solid path, direct route, general path).
#include <gtest/gtest.h>

#include "support/boolean_checks.hpp"

namespace ember::test {
namespace {

using Op = Operation;

bool same_bytes(const BooleanResult& a, const BooleanResult& b) {
  if (a.mesh.indices != b.mesh.indices || a.mesh.face_offsets != b.mesh.face_offsets) return false;
  if (a.mesh.vertices.size() != b.mesh.vertices.size()) return false;
  for (std::size_t i = 0; i < a.mesh.vertices.size(); ++i) {
    const Vec3d p = a.mesh.vertices[i], q = b.mesh.vertices[i];
    if (p.x != q.x || p.y != q.y || p.z != q.z) return false;
  }
  return true;
}

Csg op(std::size_t i) { return Csg::operand(i); }

TEST(Expressions, TheBuiltInOperationsAsExpressionsGiveTheirBytes) {
  const std::vector<Mesh> all = four_solids();
  for (const std::size_t n : {std::size_t{2}, std::size_t{3}}) {
    const std::span<const Mesh> ops(all.data(), n);
    for (const BooleanOptions& options : {BooleanOptions{}, general_path()})
      for (Op o : {Op::Union, Op::Intersection, Op::Difference, Op::Xor}) {
        const BooleanResult built_in = boolean(ops, o, options);
        const BooleanResult expression = run_checked(ops, Csg::of(o, n), options);
        EXPECT_TRUE(same_bytes(built_in, expression)) << "n=" << n << " op " << int(o);
        EXPECT_EQ(built_in.stats.diagnostic("solid_path"), expression.stats.diagnostic("solid_path"));
        EXPECT_EQ(built_in.stats.diagnostic("direct_mesh"), expression.stats.diagnostic("direct_mesh"));
      }
  }
}

TEST(Expressions, VolumeIdentitiesHoldBetweenExpressions) {
  const std::vector<Mesh> ops = four_solids();
  const std::span<const Mesh> ab(ops.data(), 2), abc(ops.data(), 3);
  const Csg a = op(0), b = op(1), c = op(2), d = op(3);
  const auto vol = [](std::span<const Mesh> operands, const Csg& e) { return volume(run_checked(operands, e).mesh); };
  const double v_or = vol(ab, a | b), v_and = vol(ab, a & b);
  EXPECT_TRUE(close_rel(v_or + v_and, volume(ops[0]) + volume(ops[1]), 1e-9)) << v_or << " + " << v_and;
  EXPECT_TRUE(close_rel(vol(ab, a ^ b), v_or - v_and, 1e-9));
  // (A | B) - C and (A | B) & C partition A | B.
  EXPECT_TRUE(close_rel(vol(abc, (a | b) - c) + vol(abc, (a | b) & c), v_or, 1e-9));
  // Inclusion-exclusion on (A ^ B) | (C - D).
  const double v_x = vol(ab, a ^ b), v_cd = vol(std::span<const Mesh>(ops.data() + 2, 2), op(0) - op(1));
  EXPECT_TRUE(close_rel(vol(ops, (a ^ b) | (c - d)), v_x + v_cd - vol(ops, (a ^ b) & (c - d)), 1e-9));
  // The layers at_least(k) for k = 1..4 stack up to the operands' volumes.
  double layers = 0;
  for (int k = 1; k <= 4; ++k) layers += vol(ops, Csg::at_least(k, {a, b, c, d}));
  EXPECT_TRUE(close_rel(layers, volume(std::span<const Mesh>(ops)), 1e-9));
}

struct Case {
  const char* name;
  Csg expression;
  std::size_t operands;
};

std::vector<Case> expressions() {
  const Csg a = op(0), b = op(1), c = op(2), d = op(3);
  return {{"((A|B)-C)&D", ((a | b) - c) & d, 4},
          {"(A^B)|(C-D)", (a ^ b) | (c - d), 4},
          {"at_least(2, A, B|C, D)", Csg::at_least(2, {a, b | c, d}), 4},
          {"(A-B)|(A&C) (A used twice)", (a - b) | (a & c), 3},
          {"B-A (two operands)", b - a, 2}};
}

TEST(Expressions, WindingNumbersAtSamplePointsAgreeOnEveryRoute) {
  const std::vector<Mesh> all = four_solids();
  for (const Case& c : expressions()) {
    const std::span<const Mesh> ops(all.data(), c.operands);
    const Indicator indicator = [e = c.expression](WindingVector w) { return e.inside(w); };
    for (const BooleanOptions& options : {BooleanOptions{}, general_path()}) {
      const BooleanResult r = run_checked(ops, c.expression, options);
      EXPECT_GT(r.mesh.face_count(), 0u) << c.name;
      const MembershipReport m = membership_check(ops, indicator, r.mesh, 300, 17);
      EXPECT_EQ(m.mismatches, 0) << c.name << ": " << m.first;
      EXPECT_GE(m.checked, 250) << c.name;
      // The custom indicator (no early terminations) gives the same solid.
      BooleanOptions custom = options;
      custom.indicator = indicator;
      const BooleanResult u = boolean(ops, Op::Union, custom);
      EXPECT_TRUE(close_rel(volume(r.mesh), volume(u.mesh), 1e-9)) << c.name;
      EXPECT_TRUE(close_rel(surface_area(r.mesh), surface_area(u.mesh), 1e-9)) << c.name;
    }
  }
}

TEST(Expressions, OneAndTwoThreadsGiveIdenticalBytes) {
  const std::vector<Mesh> all = four_solids();
  for (const Case& c : expressions())
    for (BooleanOptions options : {BooleanOptions{}, general_path()}) {
      const std::span<const Mesh> ops(all.data(), c.operands);
      options.threads = 1;
      const BooleanResult one = boolean(ops, c.expression, options);
      options.threads = 2;
      const BooleanResult two = boolean(ops, c.expression, options);
      EXPECT_TRUE(same_bytes(one, two)) << c.name;
      EXPECT_EQ(one.provenance.size(), two.provenance.size()) << c.name;
    }
}

TEST(Expressions, TwoOperandExpressionsTakeTheDirectRoute) {
  const std::vector<Mesh> all = four_solids();
  const std::span<const Mesh> ab(all.data(), 2);
  const BooleanResult r = run_checked(ab, op(1) - op(0));
  EXPECT_EQ(r.stats.diagnostic("direct_mesh"), 1.0);
  const std::vector<Mesh> swapped{all[1], all[0]};
  const BooleanResult d = boolean(swapped, Op::Difference);
  EXPECT_TRUE(close_rel(volume(r.mesh), volume(d.mesh), 1e-9));
  // Three solid operands: the solid path.
  EXPECT_EQ(run_checked(std::span<const Mesh>(all.data(), 3), (op(0) | op(1)) - op(2)).stats.diagnostic("solid_path"),
            1.0);
}

TEST(Expressions, MisuseIsAnErrorThatSaysWhatToFix) {
  const std::vector<Mesh> all = four_solids();
  const std::span<const Mesh> abc(all.data(), 3);
  EXPECT_NE(error_message([&] { boolean(abc, op(0) | op(1)); }).find("operand 2: the expression does not use"),
            std::string::npos);
  EXPECT_NE(error_message([&] { boolean(abc, op(0) | op(3)); }).find("uses operand 3 but only 3"), std::string::npos);
  BooleanOptions k;
  k.min_k = 2;
  EXPECT_NE(error_message([&] { boolean(abc, op(0) | op(1) | op(2), k); }).find("Csg::at_least"), std::string::npos);
  EXPECT_NE(error_message([&] { boolean(abc, Csg()); }).find("empty"), std::string::npos);
}

}  // namespace
}  // namespace ember::test
