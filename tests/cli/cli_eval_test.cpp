// `ember eval EXPR`: expressions over mesh files as one Boolean. Results are
// checked against the operation commands and exact box volumes; syntax errors
// must point at their column and leave no output.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "ember/io/mesh_io.hpp"
#include "ember/shapes.hpp"
#include "support/cli_harness.hpp"
#include "support/mesh_checks.hpp"
#include "support/shapes.hpp"

namespace {

using namespace ember::clitest;
using ember::Mesh;
using ember::test::box;
using ember::test::volume;

/// Boxes with integer corners, so every volume below is exact:
/// a = [0,2]^3, b = [1,3]^3, c = [1,2] x [1,2] x [-1,4], d = [0,3] x [0,3] x [1.5,4].
void put_boxes(const TempDir& dir) {
  ember::write_mesh(box({0, 0, 0}, {2, 2, 2}), dir / "a.obj");
  ember::write_mesh(box({1, 1, 1}, {3, 3, 3}), dir / "b.stl");
  ember::write_mesh(box({1, 1, -1}, {2, 2, 4}), dir / "c.ply");
  ember::write_mesh(box({0, 0, 1.5}, {3, 3, 4}), dir / "d.off");
}

double volume_of(const TempDir& dir, const std::string& name) { return volume(ember::read_mesh(dir / name)); }

TEST(CliEval, ExpressionsGiveTheExactVolumes) {
  TempDir dir;
  put_boxes(dir);
  struct Case {
    const char* expression;
    double volume;
  };
  // c meets a | b in [1,2]^2 x [0,3] (3); (a | b) & d = 7.5, of which c takes
  // [1,2]^2 x [1.5,3] (1.5); c - d = [1,2]^2 x [-1,1.5] (2.5) meets a ^ b in
  // [1,2]^2 x [0,1] (1).
  for (const Case& c :
       {Case{"a.obj | b.stl", 15}, Case{"a.obj & b.stl", 1}, Case{"a.obj - b.stl", 7}, Case{"a.obj ^ b.stl", 14},
        Case{"(a.obj | b.stl) - c.ply", 12}, Case{"((a.obj | b.stl) - c.ply) & d.off", 6},
        Case{"(a.obj ^ b.stl) | (c.ply - d.off)", 15.5}, Case{"(a.obj|b.stl)-(c.ply)", 12}}) {
    const RunResult r = run_cli(dir, {"eval", c.expression, "-o", "out.obj"});
    ASSERT_EQ(r.exit_code, 0) << describe(r);
    EXPECT_EQ(volume_of(dir, "out.obj"), c.volume) << c.expression;
  }
}

TEST(CliEval, ASimpleExpressionGivesTheOperationCommandsBytes) {
  TempDir dir;
  put_boxes(dir);
  const Mesh torus = ember::shapes::torus(1.0, 0.35, 48, 24);
  const Mesh sphere = ember::shapes::uv_sphere({0.9, 0.0, 0.2}, 0.6, 32, 16);
  ember::write_mesh(torus, dir / "torus.obj");
  ember::write_mesh(sphere, dir / "sphere.obj");
  for (const auto& [command, symbol] : std::vector<std::pair<std::string, std::string>>{
           {"union", " | "}, {"intersection", " & "}, {"difference", " - "}, {"xor", " ^ "}}) {
    ASSERT_EQ(run_cli(dir, {command, "torus.obj", "sphere.obj", "a.obj", "-o", "op.ply"}).exit_code, 0);
    const RunResult r = run_cli(dir, {"eval", "torus.obj" + symbol + "sphere.obj" + symbol + "a.obj", "-o", "ex.ply"});
    ASSERT_EQ(r.exit_code, 0) << describe(r);
    EXPECT_EQ(read_file(dir / "op.ply"), read_file(dir / "ex.ply")) << command;
  }
}

TEST(CliEval, AFileNamedTwiceIsOneOperandReadOnce) {
  TempDir dir;
  put_boxes(dir);
  const RunResult r = run_cli(dir, {"eval", "(a.obj | b.stl) - (a.obj & b.stl)", "-o", "x.obj", "--stats"});
  ASSERT_EQ(r.exit_code, 0) << describe(r);
  EXPECT_EQ(volume_of(dir, "x.obj"), 14);  // a ^ b
  EXPECT_NE(r.err.find("\"input_triangles\": 24,"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("\"operation\": \"(a.obj | b.stl) - (a.obj & b.stl)\""), std::string::npos) << r.err;
}

TEST(CliEval, QuotedNamesMayHoldSpacesAndOperators) {
  TempDir dir;
  put_boxes(dir);
  ember::write_mesh(box({0, 0, 0}, {2, 2, 2}), dir / "my part (1).obj");
  ember::write_mesh(box({1, 1, 1}, {3, 3, 3}), dir / "x-y|z.stl");
  ember::write_mesh(box({1, 1, 1}, {3, 3, 3}), dir / "tool-2.stl");
  for (const std::string e : {"'my part (1).obj' - \"x-y|z.stl\"", "'my part (1).obj' - tool-2.stl"}) {
    const RunResult r = run_cli(dir, {"eval", e, "-o", "o.obj"});
    ASSERT_EQ(r.exit_code, 0) << describe(r);
    EXPECT_EQ(volume_of(dir, "o.obj"), 7) << e;
  }
}

TEST(CliEval, SyntaxErrorsPointAtTheirColumnAndWriteNothing) {
  TempDir dir;
  put_boxes(dir);
  struct Case {
    const char* expression;
    const char* message;
    std::size_t column;
  };
  for (const Case& c :
       {Case{"a.obj | b.stl & c.ply", "'&' after '|' without parentheses", 15},
        Case{"(a.obj | b.stl", "this '(' is not closed", 1}, Case{"a.obj | b.stl)", "a ')' without its '('", 14},
        Case{"a.obj |", "the expression ends", 8}, Case{"a.obj b.stl", "an operator (| & - ^) or the end expected", 7},
        Case{"a.obj | 'b.stl", "this quote is not closed", 9}, Case{"a.obj | ()", "a file name or '(' expected", 10},
        Case{"", "the expression ends", 1}}) {
    const RunResult r = run_cli(dir, {"eval", c.expression, "-o", "o.obj"});
    EXPECT_EQ(r.exit_code, 2) << describe(r);
    EXPECT_NE(r.err.find(c.message), std::string::npos) << describe(r);
    EXPECT_NE(r.err.find("column " + std::to_string(c.column) + ":"), std::string::npos) << describe(r);
    // The caret sits under the column (the expression is indented by two).
    const std::vector<std::string> lines = lines_of(r.err);
    ASSERT_GE(lines.size(), 3u) << r.err;
    EXPECT_EQ(lines[2].find('^'), c.column + 1) << r.err;
    EXPECT_FALSE(fs::exists(dir / "o.obj"));
  }
}

TEST(CliEval, OperandErrorsNameTheFile) {
  TempDir dir;
  put_boxes(dir);
  write_file(dir / "empty.obj", "# nothing\n");
  RunResult r = run_cli(dir, {"eval", "a.obj - missing.stl", "-o", "o.obj"});
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("missing.stl"), std::string::npos) << r.err;
  r = run_cli(dir, {"eval", "a.obj - empty.obj", "-o", "o.obj"});
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("empty.obj"), std::string::npos) << r.err;
  // One 3MF file with two objects cannot be one operand.
  const std::vector<Mesh> objects{box({0, 0, 0}, {1, 1, 1}), box({5, 0, 0}, {6, 1, 1})};
  write_file(dir / "two.3mf", ember::write_3mf(objects));
  r = run_cli(dir, {"eval", "a.obj - two.3mf", "-o", "o.obj"});
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("two.3mf: holds 2 objects"), std::string::npos) << r.err;
  r = run_cli(dir, {"eval", "a.obj - b.stl", "-o", "o.obj", "--min-k", "2"});
  EXPECT_EQ(r.exit_code, 2) << describe(r);
  EXPECT_FALSE(fs::exists(dir / "o.obj"));
}

TEST(CliEval, ThreadsDoNotChangeTheBytesAndTheOptionsApply) {
  TempDir dir;
  put_boxes(dir);
  ember::write_mesh(ember::shapes::torus(1.0, 0.35, 48, 24), dir / "torus.obj");
  ember::write_mesh(ember::shapes::uv_sphere({0.9, 0.0, 0.2}, 0.6, 32, 16), dir / "sphere.obj");
  const std::string e = "(torus.obj ^ sphere.obj) | (a.obj - b.stl)";
  ASSERT_EQ(run_cli(dir, {"eval", e, "-o", "one.obj", "--threads", "1", "--no-solid-check"}).exit_code, 0);
  ASSERT_EQ(run_cli(dir, {"eval", e, "-o", "two.obj", "--threads", "2", "--no-solid-check"}).exit_code, 0);
  EXPECT_EQ(read_file(dir / "one.obj"), read_file(dir / "two.obj"));
  ASSERT_EQ(run_cli(dir, {"eval", e, "-o", "p.obj", "--polygons", "--quiet", "--assume-solid"}).exit_code, 0);
  EXPECT_TRUE(fs::exists(dir / "p.obj"));
}

}  // namespace

namespace {

TEST(CliLayers, UnionLayersWriteOneFilePerLayerWithTheExactVolumes) {
  TempDir dir;
  put_boxes(dir);
  const RunResult r = run_cli(dir, {"union", "a.obj", "b.stl", "c.ply", "d.off", "--layers", "-o", "L.obj", "--stats"});
  ASSERT_EQ(r.exit_code, 0) << describe(r);
  // Each layer equals the --min-k run of its k.
  double stacked = 0;
  for (int k = 1; k <= 4; ++k) {
    const std::string layer = "L-" + std::to_string(k) + ".obj";
    ASSERT_TRUE(fs::exists(dir / layer)) << layer;
    ASSERT_EQ(run_cli(dir, {"union", "a.obj", "b.stl", "c.ply", "d.off", "--min-k", std::to_string(k), "-o", "k.obj"})
                  .exit_code,
              0);
    EXPECT_EQ(volume_of(dir, layer), volume_of(dir, "k.obj")) << layer;
    stacked += volume_of(dir, layer);
    EXPECT_NE(r.err.find("\"operation\": \"union --layers (layer " + std::to_string(k) + ")\""), std::string::npos);
  }
  EXPECT_EQ(stacked, 8 + 8 + 5 + 22.5);  // the operands' volumes
  EXPECT_FALSE(fs::exists(dir / "L-5.obj"));
}

TEST(CliLayers, LayersApplyToUnionAloneAndNotWithMinK) {
  TempDir dir;
  put_boxes(dir);
  RunResult r = run_cli(dir, {"intersection", "a.obj", "b.stl", "--layers", "-o", "L.obj"});
  EXPECT_EQ(r.exit_code, 2) << describe(r);
  EXPECT_NE(r.err.find("--layers applies to 'union' only"), std::string::npos) << r.err;
  r = run_cli(dir, {"union", "a.obj", "b.stl", "--layers", "--min-k", "2", "-o", "L.obj"});
  EXPECT_EQ(r.exit_code, 2) << describe(r);
  EXPECT_TRUE(dir.listing().count("L-1.obj") == 0);
}

}  // namespace
