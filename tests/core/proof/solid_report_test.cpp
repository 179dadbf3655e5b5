// Why an operand is not solid: the solid check's findings in the report and the warnings.
#include <string>

#include "support/boolean_checks.hpp"
#include "core/input/face_triangulation.hpp"
#include "core/input/quantize.hpp"

namespace ember::test {
namespace {

using Op = Operation;

bool has(const std::string& s, const std::string& part) { return s.find(part) != std::string::npos; }

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

TEST(SolidReport, SelfIntersectionCountSaysWhenItIsALowerBound) {
  OperandReport r;
  r.solid = SolidStatus::SelfIntersecting;
  r.self_intersecting_pairs = 7;
  EXPECT_EQ(describe_solid_check(r),
            "not solid: self-intersecting (7 triangle pairs meet beyond a shared vertex or edge)");
  r.self_intersecting_pairs_complete = false;  // the search stopped counting
  EXPECT_EQ(describe_solid_check(r),
            "not solid: self-intersecting (at least 7 triangle pairs meet beyond a shared vertex or edge)");
  r.self_intersecting_pairs_complete = true;
  r.self_intersecting_pairs = OperandReport::kMaxReportedPairs;  // the cap on pairs found
  EXPECT_EQ(describe_solid_check(r), "not solid: self-intersecting (at least " +
                                         std::to_string(OperandReport::kMaxReportedPairs) +
                                         " triangle pairs meet beyond a shared vertex or edge)");
}

}  // namespace
}  // namespace ember::test
