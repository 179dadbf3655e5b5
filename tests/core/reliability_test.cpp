// No silent wrong result from the grid (collapsed / flipped
// triangles, subnormal extents), the solid check's reasons in the stats, and
// exact triangulation of concave n-gons before the solid proof.
#include <string>

#include "core/core_test_util.hpp"
#include "core/input/face_triangulation.hpp"
#include "core/input/quantize.hpp"

namespace ember::test {
namespace {

using Op = Operation;

bool has(const std::string& s, const std::string& part) { return s.find(part) != std::string::npos; }

// ---- item 1: an operand the grid cannot hold is an error, never a wrong answer ----

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

// ---- item 2: a few collapsed triangles warn, with counts and the grid step -------

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

// ---- item 3: subnormal-range extents are refused ------------------------------

TEST(GridLimits, SubnormalRangeExtentIsRefusedWithAClearMessage) {
  const std::string msg = error_message([] { (void)Quantizer::fit(std::vector<Vec3d>{{0, 0, 0}, {1e-300, 1e-300, 1e-300}}); });
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

// ---- item 9: why an operand is not solid ---------------------------------------

TEST(SolidReport, SelfIntersectingOperandIsCountedAndWarned) {
  const Mesh a = self_intersecting_pair({0, 0, 0}, {2, 2, 2}, {1, 1, 1}, {3, 3, 3});
  const BooleanResult r = boolean({a, box({5, 5, 5}, {6, 6, 6})}, Op::Union);
  const OperandReport& o = r.stats.operands[0];
  EXPECT_EQ(o.solid, SolidStatus::SelfIntersecting);
  EXPECT_GT(o.self_intersecting_pairs, 0u);
  EXPECT_LT(o.self_intersecting_pairs, OperandReport::kMaxReportedPairs);
  EXPECT_EQ(r.stats.operands[1].solid, SolidStatus::Proven);
  ASSERT_EQ(r.warnings.size(), 1u);
  EXPECT_TRUE(has(r.warnings[0], "operand 0: not solid: self-intersecting (" +
                                     std::to_string(o.self_intersecting_pairs) + " triangle pairs"))
      << r.warnings[0];
}

TEST(SolidReport, InvertedAndNestedComponentsAreCountedAsInconsistentOrientation) {
  const Mesh inverted = reverse_orientation(box({0, 0, 0}, {1, 1, 1}));
  BooleanResult r = boolean({inverted, box({5, 5, 5}, {6, 6, 6})}, Op::Union);
  EXPECT_EQ(r.stats.operands[0].solid, SolidStatus::Misoriented);
  EXPECT_EQ(r.stats.operands[0].misoriented_components, 1u);
  ASSERT_EQ(r.warnings.size(), 1u);
  EXPECT_TRUE(has(r.warnings[0], "inconsistent orientation (1 components")) << r.warnings[0];
  r = boolean({nested_shells({0, 0, 0}, {4, 4, 4}, {1, 1, 1}, {2, 2, 2}), box({5, 5, 5}, {6, 6, 6})}, Op::Union);
  EXPECT_EQ(r.stats.operands[0].solid, SolidStatus::Misoriented);
  EXPECT_EQ(r.stats.operands[0].misoriented_components, 1u);  // the inner shell has winding 1 in front
}

TEST(SolidReport, OpenPromisedAndUncheckedOperandsAreReported) {
  Mesh open = box({0, 0, 0}, {1, 1, 1});
  open.indices.resize(open.indices.size() - 3);
  open.face_offsets.pop_back();
  BooleanOptions opt;
  opt.allow_open = true;
  opt.solid = {false, true};
  BooleanResult r = boolean({open, box({5, 5, 5}, {6, 6, 6})}, Op::Union, opt);
  EXPECT_EQ(r.stats.operands[0].solid, SolidStatus::Open);
  EXPECT_EQ(r.stats.operands[0].open_edges, 3u);
  EXPECT_EQ(r.stats.operands[1].solid, SolidStatus::Promised);
  opt.detect_solid = false;
  opt.solid = {};
  r = boolean({open, box({5, 5, 5}, {6, 6, 6})}, Op::Union, opt);
  EXPECT_EQ(r.stats.operands[1].solid, SolidStatus::NotChecked);
  EXPECT_EQ(describe_solid_check(r.stats.operands[0]), "not solid: open (3 edges not matched by an opposite edge)");
}

TEST(Reliability, SelfIntersectionCountSaysWhenItIsALowerBound) {
  OperandReport r;
  r.solid = SolidStatus::SelfIntersecting;
  r.self_intersecting_pairs = 7;
  EXPECT_EQ(describe_solid_check(r), "not solid: self-intersecting (7 triangle pairs meet beyond a shared vertex or edge)");
  r.self_intersecting_pairs_complete = false;  // the search stopped counting
  EXPECT_EQ(describe_solid_check(r),
            "not solid: self-intersecting (at least 7 triangle pairs meet beyond a shared vertex or edge)");
  r.self_intersecting_pairs_complete = true;
  r.self_intersecting_pairs = OperandReport::kMaxReportedPairs;  // the cap on pairs found
  EXPECT_EQ(describe_solid_check(r), "not solid: self-intersecting (at least " +
                                         std::to_string(OperandReport::kMaxReportedPairs) +
                                         " triangle pairs meet beyond a shared vertex or edge)");
}

// ---- item 10: concave n-gons are triangulated exactly ---------------------------

/// An L-shaped prism whose two caps are concave hexagons (one face each).
Mesh l_prism() {
  Mesh m;
  const double xy[6][2] = {{0, 0}, {3, 0}, {3, 1}, {1, 1}, {1, 3}, {0, 3}};
  for (const double z : {0.0, 1.0})
    for (const auto& p : xy) m.add_vertex({p[0], p[1], z});
  m.add_face({5, 4, 3, 2, 1, 0});   // bottom, facing -z
  m.add_face({6, 7, 8, 9, 10, 11});  // top, facing +z
  for (std::uint32_t i = 0; i < 6; ++i) {
    const std::uint32_t j = (i + 1) % 6;
    m.add_face({i, j, j + 6, i + 6});
  }
  return m;
}

TEST(ConcaveFaces, LPrismWithHexagonCapsIsProvenSolidAndExact) {
  const Mesh l = l_prism();
  const BooleanResult r = run_checked({l, box({2, 0, 0}, {4, 1, 1})}, Op::Union);
  EXPECT_EQ(r.stats.operands[0].solid, SolidStatus::Proven) << describe_solid_check(r.stats.operands[0]);
  EXPECT_TRUE(r.warnings.empty()) << r.warnings[0];
  EXPECT_EQ(volume(r.mesh), 6.0);  // 5 + 2 - overlap 1
}

/// Twice the signed projected (xy) area of triangles over the corners.
std::int64_t twice_area(std::span<const IntPoint> c, const std::vector<std::array<std::uint32_t, 3>>& tris, bool& ccw) {
  std::int64_t sum = 0;
  ccw = true;
  for (const auto& t : tris) {
    const IntPoint &a = c[t[0]], &b = c[t[1]], &d = c[t[2]];
    const std::int64_t o = (b.x - a.x) * (d.y - a.y) - (b.y - a.y) * (d.x - a.x);
    ccw &= o > 0;
    sum += o;
  }
  return sum;
}

TEST(ConcaveFaces, EarClippingCoversTheFaceWithPositiveTriangles) {
  // A comb: concave at three corners; the fan from corner 0 would overlap.
  const std::vector<IntPoint> comb{{0, 0, 5}, {6, 0, 5}, {6, 4, 5}, {5, 4, 5}, {5, 1, 5},
                                   {3, 1, 5}, {3, 4, 5}, {2, 4, 5}, {2, 1, 5}, {1, 1, 5}, {1, 4, 5}, {0, 4, 5}};
  std::vector<std::array<std::uint32_t, 3>> tris;
  core::triangulate_polygon(comb, tris);
  ASSERT_EQ(tris.size(), comb.size() - 2);
  bool ccw = false;
  EXPECT_EQ(twice_area(comb, tris, ccw), 2 * (6 * 1 + 3 * 3));
  EXPECT_TRUE(ccw);
  // A figure eight has no area and no ear clipping: the fan is kept (it
  // gives the same winding numbers as the face).
  const std::vector<IntPoint> eight{{0, 0, 0}, {2, 2, 0}, {2, 0, 0}, {0, 2, 0}};
  tris.clear();
  core::triangulate_polygon(eight, tris);
  EXPECT_EQ(tris, (std::vector<std::array<std::uint32_t, 3>>{{0, 1, 2}, {0, 2, 3}}));
}

}  // namespace
}  // namespace ember::test
