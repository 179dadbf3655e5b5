// No silent wrong result from the grid: an operand the grid erases or turns
// inside out is an error, collapsed and flipped triangles are counted and
// warned about, subnormal extents are refused.
#include <string>

#include "support/boolean_checks.hpp"
#include "core/input/face_triangulation.hpp"
#include "core/input/quantize.hpp"

namespace ember::test {
namespace {

using Op = Operation;

bool has(const std::string& s, const std::string& part) { return s.find(part) != std::string::npos; }

TEST(GridLimits, UnitCubeBesideAHugeSlabIsAnErrorNamingOperandCountsAndStep) {
  const Mesh cube = box({0, 0, 0}, {1, 1, 1});
  const Mesh slab = box({-1e30, -1e30, 0.5}, {1e30, 1e30, 1e30});
  const std::string msg = error_message([&] { (void)boolean({cube, slab}, Op::Difference); });
  EXPECT_TRUE(has(msg, "operand 0:")) << msg;
  EXPECT_TRUE(has(msg, "12 of its 12 triangles collapse")) << msg;
  EXPECT_TRUE(has(msg, "step 3.78e+22")) << msg;
}

TEST(GridLimits, OneVertexAt1e300ErasingTheOtherOperandIsAnError) {
  Mesh far = tetrahedron({0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1e300});
  const Mesh cube = box({0, 0, 0}, {1, 1, 1});
  const std::string msg = error_message([&] { (void)boolean({cube, far}, Op::Union); });
  EXPECT_TRUE(has(msg, "operand 0:")) << msg;
  EXPECT_TRUE(has(msg, "collapse")) << msg;
}

// ---- a few collapsed triangles warn, with counts and the grid step -------

TEST(GridLimits, SubGridComponentWarnsAndIsCounted) {
  // A 1e-9 cube beside a finely tessellated unit sphere in one operand: its
  // 12 triangles collapse (step 2^-25 ~ 3e-8), the sphere is intact.
  const Mesh a = merge({icosphere({0, 0, 0}, 1.0, 3), box({0.1, 0.1, 0.1}, {0.1 + 1e-9, 0.1 + 1e-9, 0.1 + 1e-9})});
  const Mesh b = box({0, 0, 0}, {2, 2, 2});
  const BooleanResult r = boolean({a, b}, Op::Union);
  EXPECT_EQ(r.stats.collapsed_triangles, 12u);
  EXPECT_EQ(r.stats.operands[0].collapsed_triangles, 12u);
  EXPECT_EQ(r.stats.operands[1].collapsed_triangles, 0u);
  EXPECT_EQ(r.stats.flipped_triangles, 0u);
  EXPECT_EQ(r.stats.grid_step, std::ldexp(1.0, -24));
  bool warned = false;
  for (const std::string& w : r.warnings)
    warned |= has(w, "operand 0: 12 of its") && has(w, "collapse") && has(w, "step 5.96e-08");
  EXPECT_TRUE(warned) << (r.warnings.empty() ? "no warnings" : r.warnings[0]);
}

TEST(GridLimits, CleanInputsHaveNoQuantizationWarning) {
  const BooleanResult r = boolean({box({0, 0, 0}, {2, 2, 2}), box({1, 1, 1}, {3, 3, 3})}, Op::Union);
  EXPECT_EQ(r.stats.collapsed_triangles, 0u);
  EXPECT_EQ(r.stats.flipped_triangles, 0u);
  EXPECT_TRUE(r.warnings.empty()) << r.warnings[0];
}

// ---- subnormal-range extents are refused ------------------------------

TEST(GridLimits, SubnormalRangeExtentIsRefusedWithAClearMessage) {
  const std::string msg = error_message([] {
    (void)Quantizer::fit(std::vector<Vec3d>{{0, 0, 0}, {1e-300, 1e-300, 1e-300}});
  });
  EXPECT_TRUE(has(msg, "too small")) << msg;
  EXPECT_TRUE(has(msg, "scale the model up")) << msg;
  const std::string sub = error_message([] { (void)Quantizer::fit(std::vector<Vec3d>{{0, 0, 0}, {5e-320, 0, 0}}); });
  EXPECT_TRUE(has(sub, "too small")) << sub;
  // Just above the limit the map still works and is exact for dyadic inputs.
  const std::vector<Vec3d> ok{{0, 0, 0}, {std::ldexp(1.0, -970), std::ldexp(3.0, -972), 0}};
  const Quantizer q = Quantizer::fit(ok);
  for (const Vec3d& p : ok) EXPECT_EQ(q.dequantize(q.quantize(p)), p);
  const Mesh tiny = scale(box({0, 0, 0}, {1, 1, 1}), 1e-300);
  EXPECT_TRUE(has(error_message([&] { (void)boolean({tiny, tiny}, Op::Union); }), "too small"));
}

}  // namespace
}  // namespace ember::test
