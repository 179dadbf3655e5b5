// End-to-end tests of the `ember` command line: each test runs the built binary
// (EMBER_CLI_PATH) in a fresh temporary directory, then checks the exit status,
// stderr, and the files it wrote (read back with the library's readers).
//
// Box inputs have integer coordinates, so every expected volume is exact.
#include <gtest/gtest.h>

#include <cstring>

#include <cmath>
#include <map>
#include <regex>
#include <string>
#include <vector>

#include "support/cli_harness.hpp"
#include "ember/boolean.hpp"
#include "ember/io/mesh_io.hpp"
#include "support/mesh_checks.hpp"
#include "support/shapes.hpp"

namespace {

using namespace ember::clitest;
using ember::Mesh;
using ember::Operation;
using ember::test::box;
using ember::test::Box;
using ember::test::volume;

// A = [0,2]^3, B = [1,3]^3: vol 8 each, overlap [1,2]^3 = 1.
Mesh box_a() { return box({0, 0, 0}, {2, 2, 2}); }
Mesh box_b() { return box({1, 1, 1}, {3, 3, 3}); }

/// An input path in the test directory with the mesh written to it.
std::string put(const TempDir& dir, const std::string& name, const Mesh& m) {
  const fs::path p = dir / name;
  ember::write_mesh(m, p);
  return p.string();
}

/// The box A with its +z face (two triangles) removed: 4 open edges.
Mesh open_box() {
  Mesh full = box_a();
  Mesh m;
  m.vertices = full.vertices;
  for (std::size_t f = 0; f < full.face_count(); ++f) {
    auto face = full.face(f);
    bool top = true;
    for (std::uint32_t v : face) top = top && full.vertices[v].z == 2;
    if (!top) m.add_face(face);
  }
  return m;
}

/// stderr is exactly one line "ember: <file>: <problem>" (README's format).
void expect_file_error(const RunResult& r, const std::string& file) {
  EXPECT_EQ(r.exit_code, 1) << describe(r);
  EXPECT_FALSE(r.signaled) << describe(r);
  const auto lines = lines_of(r.err);
  ASSERT_EQ(lines.size(), 1u) << "expected one error line\n" << describe(r);
  EXPECT_EQ(lines[0].rfind("ember: " + file + ":", 0), 0u) << "error line should start with 'ember: " << file << ":'\n"
                                                           << describe(r);
}

/// A usage error: exit 2, a non-empty message on stderr.
void expect_usage_error(const RunResult& r) {
  EXPECT_EQ(r.exit_code, 2) << describe(r);
  EXPECT_FALSE(r.signaled) << describe(r);
  EXPECT_FALSE(r.err.empty()) << describe(r);
  EXPECT_NE(r.err.find("ember"), std::string::npos) << describe(r);
}

/// Reads a result file; it must exist and hold structurally sound, exactly
/// convex and planar polygons (integer box results).
Mesh read_result(const fs::path& p) {
  EXPECT_TRUE(fs::exists(p)) << p;
  Mesh m = ember::read_mesh(p);
  EXPECT_EQ(ember::test::face_problems(m, 0), "") << p;
  return m;
}

// ---- the four operations -----------------------------------------------------

struct OpCase {
  const char* op;
  Operation operation;
  double volume;
};

void PrintTo(const OpCase& c, std::ostream* os) { *os << c.op << " (volume " << c.volume << ")"; }

class CliOperation : public ::testing::TestWithParam<OpCase> {};

TEST_P(CliOperation, TwoOverlappingBoxesObjExactVolume) {
  const OpCase c = GetParam();
  TempDir dir;
  const std::string a = put(dir, "a.obj", box_a()), b = put(dir, "b.obj", box_b());
  const RunResult r = run_cli(dir, {c.op, a, b, "-o", (dir / "out.obj").string()});
  ASSERT_EQ(r.exit_code, 0) << describe(r);
  EXPECT_EQ(r.err, "") << "a successful run without --stats should be silent on stderr\n" << describe(r);
  const Mesh m = read_result(dir / "out.obj");
  EXPECT_GT(m.face_count(), 0u);
  EXPECT_EQ(volume(m), c.volume) << c.op;
  const Mesh ops[] = {box_a(), box_b()};
  const auto rep = ember::test::membership_check(ops, c.operation, m, 200, 7);
  EXPECT_EQ(rep.mismatches, 0) << rep.first;
  EXPECT_GT(rep.checked, 100);
  // Nothing but the inputs and the result in the directory (no temporary left).
  EXPECT_EQ(dir.listing(), (std::set<std::string>{"a.obj", "b.obj", "out.obj"}));
}

INSTANTIATE_TEST_SUITE_P(Ops, CliOperation,
                         ::testing::Values(OpCase{"union", Operation::Union, 15},
                                           OpCase{"intersection", Operation::Intersection, 1},
                                           OpCase{"difference", Operation::Difference, 7},
                                           OpCase{"xor", Operation::Xor, 14}),
                         [](const auto& info) { return std::string(info.param.op); });

TEST(Cli, MixedInputAndOutputFormats) {
  struct Combo {
    const char *a, *b, *out, *op;
    double volume;
  };
  const Combo combos[] = {
      {"stl", "ply", "off", "union", 15},       {"ply", "off", "stl", "difference", 7},
      {"off", "stl", "ply", "intersection", 1}, {"obj", "stl", "ply", "xor", 14},
      {"ply", "obj", "obj", "union", 15},       {"off", "off", "stl", "xor", 14},
  };
  for (const Combo& c : combos) {
    SCOPED_TRACE(std::string(c.a) + " " + c.op + " " + c.b + " -> " + c.out);
    TempDir dir;
    const std::string a = put(dir, std::string("a.") + c.a, box_a());
    const std::string b = put(dir, std::string("b.") + c.b, box_b());
    const fs::path out = dir / (std::string("out.") + c.out);
    const RunResult r = run_cli(dir, {c.op, a, b, "-o", out.string()});
    ASSERT_EQ(r.exit_code, 0) << describe(r);
    const Mesh m = read_result(out);
    EXPECT_EQ(volume(m), c.volume);
    // The output format follows the extension.
    const std::string bytes = read_file(out);
    const std::string fmt = c.out;
    if (fmt == "off") {
      EXPECT_EQ(bytes.rfind("OFF", 0), 0u);
    } else if (fmt == "ply") {
      EXPECT_EQ(bytes.rfind("ply\n", 0), 0u);
      // Provenance per triangle as face properties: each triangle names an
      // operand (0 or 1) and one of that box's 12 triangles.
      ASSERT_NE(bytes.find("property uint operand\nproperty uint source_face\n"), std::string::npos);
      const std::size_t body = bytes.find("end_header\n") + 11 + m.vertices.size() * 24;
      ASSERT_EQ(bytes.size(), body + m.face_count() * (1 + 12 + 8));
      for (std::size_t f = 0; f < m.face_count(); ++f) {
        std::uint32_t operand = 0, face = 0;
        std::memcpy(&operand, bytes.data() + body + f * 21 + 13, 4);
        std::memcpy(&face, bytes.data() + body + f * 21 + 17, 4);
        EXPECT_LT(operand, 2u);
        EXPECT_LT(face, 12u);
      }
    } else if (fmt == "stl") {
      EXPECT_EQ(bytes.size(), 84 + 50 * m.face_count());  // binary, triangles
    }
  }
}

TEST(Cli, AsciiStlInputAndUppercaseExtension) {
  TempDir dir;
  // Box B as a hand-written ASCII STL (fan triangles of each quad face).
  const Mesh b = box_b();
  std::string stl = "solid b\n";
  for (std::size_t f = 0; f < b.face_count(); ++f) {
    stl += "  facet normal 0 0 0\n    outer loop\n";
    for (std::uint32_t v : b.face(f)) {
      const auto& p = b.vertices[v];
      stl += "      vertex " + std::to_string(p.x) + " " + std::to_string(p.y) + " " + std::to_string(p.z) + "\n";
    }
    stl += "    endloop\n  endfacet\n";
  }
  stl += "endsolid b\n";
  write_file(dir / "b.stl", stl);
  const std::string a = put(dir, "a.obj", box_a());
  const RunResult r = run_cli(dir, {"difference", a, (dir / "b.stl").string(), "-o", (dir / "OUT.OBJ").string()});
  ASSERT_EQ(r.exit_code, 0) << describe(r);
  EXPECT_EQ(volume(read_result(dir / "OUT.OBJ")), 7);
}

TEST(Cli, RelativePathsWithSpacesAndQuotes) {
  TempDir dir;
  put(dir, "box a.obj", box_a());
  put(dir, "it's b.ply", box_b());
  const RunResult r = run_cli(dir, {"union", "box a.obj", "it's b.ply", "-o", "the result.off"});
  ASSERT_EQ(r.exit_code, 0) << describe(r);
  EXPECT_EQ(volume(read_result(dir / "the result.off")), 15);
}

// ---- n-ary and --min-k -----------------------------------------------------------

// A = [0,2]^3, B = [1,3]x[0,2]x[0,2], C = [0,2]x[1,3]x[1,3]
const std::vector<std::vector<Box>> kThree = {
    {{{0, 0, 0}, {2, 2, 2}}}, {{{1, 0, 0}, {3, 2, 2}}}, {{{0, 1, 1}, {2, 3, 3}}}};

TEST(Cli, ThreeInputsNaryMatchVoxelVolumes) {
  TempDir dir;
  std::vector<std::string> in;
  const std::vector<Mesh> meshes = ember::test::box_meshes(kThree);
  const char* names[] = {"a.obj", "b.stl", "c.ply"};
  for (std::size_t i = 0; i < 3; ++i) in.push_back(put(dir, names[i], meshes[i]));
  const std::pair<const char*, Operation> ops[] = {{"union", Operation::Union},
                                                   {"intersection", Operation::Intersection},
                                                   {"difference", Operation::Difference},
                                                   {"xor", Operation::Xor}};
  for (const auto& [op, operation] : ops) {
    SCOPED_TRACE(op);
    const double expected = ember::test::voxel_volume(kThree, ember::test::reference_indicator(operation, 3));
    ASSERT_GT(expected, 0);
    const fs::path out = dir / (std::string(op) + ".obj");
    const RunResult r = run_cli(dir, {op, in[0], in[1], in[2], "-o", out.string()});
    ASSERT_EQ(r.exit_code, 0) << describe(r);
    EXPECT_EQ(volume(read_result(out)), expected);
  }
}

TEST(Cli, MinKOnThreeBoxesMatchesVoxelVolume) {
  TempDir dir;
  std::vector<std::string> in;
  const std::vector<Mesh> meshes = ember::test::box_meshes(kThree);
  for (std::size_t i = 0; i < 3; ++i) in.push_back(put(dir, "in" + std::to_string(i) + ".obj", meshes[i]));
  std::map<int, double> seen;
  for (int k = 1; k <= 3; ++k) {
    SCOPED_TRACE("k = " + std::to_string(k));
    const double expected =
        ember::test::voxel_volume(kThree, ember::test::reference_indicator(Operation::AtLeastK, 3, k));
    std::string name = "k";
    name += std::to_string(k);
    const fs::path out = dir / (name + ".obj");
    const RunResult r = run_cli(dir, {"union", in[0], in[1], in[2], "-o", out.string(), "--min-k", std::to_string(k)});
    ASSERT_EQ(r.exit_code, 0) << describe(r);
    seen[k] = volume(read_result(out));
    EXPECT_EQ(seen[k], expected);
  }
  // The three levels really differ (k = 2 is neither union nor intersection).
  EXPECT_GT(seen[1], seen[2]);
  EXPECT_GT(seen[2], seen[3]);
  EXPECT_GT(seen[3], 0);
}

TEST(Cli, MinKOutOfRangeOrWithOtherOperationsIsAnError) {
  TempDir dir;
  const std::string a = put(dir, "a.obj", box_a()), b = put(dir, "b.obj", box_b());
  const std::string out = (dir / "out.obj").string();
  // More than the number of inputs.
  RunResult r = run_cli(dir, {"union", a, b, "-o", out, "--min-k", "3"});
  EXPECT_GE(r.exit_code, 1) << describe(r);
  EXPECT_LE(r.exit_code, 127) << describe(r);
  EXPECT_NE(r.err.find("min", 0), std::string::npos) << describe(r);
  EXPECT_FALSE(fs::exists(out));
  // --min-k 0: rejected by the option parser.
  expect_usage_error(run_cli(dir, {"union", a, b, "-o", out, "--min-k", "0"}));
  EXPECT_FALSE(fs::exists(out));
  // --min-k with anything but union.
  for (const char* op : {"intersection", "difference", "xor"}) {
    SCOPED_TRACE(op);
    r = run_cli(dir, {op, a, b, "-o", out, "--min-k", "2"});
    EXPECT_EQ(r.exit_code, 2) << describe(r);  // a usage error
    EXPECT_EQ(lines_of(r.err).size(), 1u) << describe(r);
    EXPECT_NE(r.err.find("--min-k"), std::string::npos) << describe(r);
    EXPECT_NE(r.err.find("union"), std::string::npos) << describe(r);
    EXPECT_FALSE(fs::exists(out));
  }
  EXPECT_EQ(dir.listing(), (std::set<std::string>{"a.obj", "b.obj"}));
}

// ---- --stats and --threads --------------------------------------------------------

/// The value of a numeric key in a one-line JSON object, or NaN if missing.
double json_number(const std::string& line, const std::string& key) {
  const std::regex re("\"" + key + "\"\\s*:\\s*(-?[0-9]+(\\.[0-9]+)?([eE][-+]?[0-9]+)?)");
  std::smatch m;
  if (!std::regex_search(line, m, re)) return std::nan("");
  return std::stod(m[1].str());
}

TEST(Cli, StatsPrintsOneJsonObjectOnStderr) {
  for (int threads : {1, 2}) {
    SCOPED_TRACE("threads = " + std::to_string(threads));
    TempDir dir;
    const std::string a = put(dir, "a.obj", box_a()), b = put(dir, "b.obj", box_b());
    const fs::path out = dir / "out.obj";
    const RunResult r =
        run_cli(dir, {"union", a, b, "-o", out.string(), "--stats", "--threads", std::to_string(threads)});
    ASSERT_EQ(r.exit_code, 0) << describe(r);
    const auto lines = lines_of(r.err);
    ASSERT_EQ(lines.size(), 1u) << describe(r);
    const std::string& j = lines[0];
    // Shape of a flat JSON object with string or number values.
    const std::regex object(
        R"(^\{\s*"[a-z_]+"\s*:\s*("[^"]*"|-?[0-9.eE+-]+)(\s*,\s*"[a-z_]+"\s*:\s*("[^"]*"|-?[0-9.eE+-]+))*\s*\}$)");
    EXPECT_TRUE(std::regex_match(j, object)) << j;
    EXPECT_NE(j.find("\"operation\": \"union\""), std::string::npos) << j;
    EXPECT_EQ(json_number(j, "input_triangles"), 24) << j;
    EXPECT_EQ(json_number(j, "dropped_degenerate"), 0) << j;
    EXPECT_EQ(json_number(j, "threads"), threads) << j;
    const double t = json_number(j, "time_ms");
    EXPECT_GE(t, 0) << j;
    EXPECT_LT(t, 60000) << j;
    const Mesh m = read_result(out);
    EXPECT_EQ(json_number(j, "output_polygons"), static_cast<double>(m.face_count())) << j;
    EXPECT_GT(m.face_count(), 0u);
    EXPECT_EQ(r.out.find('{'), std::string::npos) << "stats belong on stderr\n" << describe(r);
  }
}

TEST(Cli, SolidCheckIsOnByDefaultAndCanBeSwitchedOff) {
  TempDir dir;
  const std::string a = put(dir, "a.obj", box_a()), b = put(dir, "b.obj", box_b());
  const fs::path out = dir / "out.obj";
  // (solid operands, solid path taken: --stats "solid_path", 1 when every operand is solid)
  const auto solid = [&](std::vector<std::string> extra) {
    std::vector<std::string> args{"union", a, b, "-o", out.string(), "--stats"};
    args.insert(args.end(), extra.begin(), extra.end());
    const RunResult r = run_cli(dir, args);
    EXPECT_EQ(r.exit_code, 0) << describe(r);
    return std::pair{json_number(r.err, "solid_operands"), json_number(r.err, "solid_path")};
  };
  EXPECT_EQ(solid({}), std::pair(2.0, 1.0));                    // both boxes proven solid
  EXPECT_EQ(solid({"--no-solid-check"}), std::pair(0.0, 0.0));  // general path
  EXPECT_EQ(solid({"--assume-solid"}), std::pair(2.0, 1.0));    // promised
  EXPECT_EQ(solid({"--assume-solid", "--no-solid-check"}), std::pair(2.0, 1.0));
}

TEST(Cli, ThreadCountDoesNotChangeTheOutputBytes) {
  TempDir dir;
  const Mesh torus = ember::test::torus({0, 0, 0}, 1.0, 0.4, 40, 20);
  const Mesh sphere = ember::test::icosphere({0.8, 0.1, 0.3}, 0.7, 3);
  const std::string a = put(dir, "torus.obj", torus), b = put(dir, "sphere.ply", sphere);
  for (const char* op : {"union", "difference", "xor"}) {
    for (const char* ext : {"obj", "ply"}) {
      SCOPED_TRACE(std::string(op) + " ." + ext);
      std::string first;
      for (const char* threads : {"1", "2", "4", "0"}) {
        const fs::path out = dir / (std::string(op) + "_t" + threads + "." + ext);
        const RunResult r = run_cli(dir, {op, a, b, "-o", out.string(), "--threads", threads});
        ASSERT_EQ(r.exit_code, 0) << describe(r);
        const std::string bytes = read_file(out);
        ASSERT_GT(bytes.size(), 100u);
        if (first.empty())
          first = bytes;
        else
          EXPECT_TRUE(bytes == first) << out << " differs from the --threads 1 output";
      }
    }
  }
}

// ---- errors -------------------------------------------------------------------

TEST(Cli, MissingInputFileIsNamedAndNoOutputIsCreated) {
  TempDir dir;
  const std::string a = put(dir, "a.obj", box_a());
  const std::string missing = (dir / "no_such_file.obj").string();
  const fs::path out = dir / "out.obj";
  const RunResult r = run_cli(dir, {"union", a, missing, "-o", out.string()});
  expect_file_error(r, missing);
  EXPECT_FALSE(fs::exists(out));
  EXPECT_EQ(dir.listing(), (std::set<std::string>{"a.obj"}));
}

TEST(Cli, MalformedObjNamesFileAndLine) {
  TempDir dir;
  const std::string a = put(dir, "a.obj", box_a());
  const std::string bad = (dir / "bad.obj").string();
  // Two good lines, then garbage bytes on line 3.
  write_file(bad, std::string("v 0 0 0\nv 1 0 0\n\x01\x02\xff garbage \x7f\n"));
  const fs::path out = dir / "out.obj";
  const RunResult r = run_cli(dir, {"intersection", a, bad, "-o", out.string()});
  expect_file_error(r, bad);
  EXPECT_EQ(r.err.rfind("ember: " + bad + ":3:", 0), 0u) << "should name line 3\n" << describe(r);
  EXPECT_FALSE(fs::exists(out));
  EXPECT_EQ(dir.listing(), (std::set<std::string>{"a.obj", "bad.obj"}));
}

TEST(Cli, FaceIndexOutOfRangeIsAnError) {
  TempDir dir;
  const std::string a = put(dir, "a.obj", box_a());
  const std::string bad = (dir / "bad.obj").string();
  write_file(bad, "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 9\n");
  const RunResult r = run_cli(dir, {"union", a, bad, "-o", (dir / "out.obj").string()});
  expect_file_error(r, bad);
  EXPECT_FALSE(fs::exists(dir / "out.obj"));
}

TEST(Cli, UnknownOutputExtensionListsSupportedFormats) {
  TempDir dir;
  const std::string a = put(dir, "a.obj", box_a()), b = put(dir, "b.obj", box_b());
  const std::string out = (dir / "out.xyz").string();
  const RunResult r = run_cli(dir, {"union", a, b, "-o", out});
  expect_file_error(r, out);
  for (const char* ext : {".obj", ".stl", ".off", ".ply"}) EXPECT_NE(r.err.find(ext), std::string::npos) << ext;
  EXPECT_EQ(dir.listing(), (std::set<std::string>{"a.obj", "b.obj"}));
}

TEST(Cli, UnknownInputExtensionIsNamed) {
  TempDir dir;
  const std::string a = put(dir, "a.obj", box_a());
  const std::string b = (dir / "b.xyz").string();
  write_file(b, read_file(put(dir, "b.obj", box_b())));
  const RunResult r = run_cli(dir, {"union", a, b, "-o", (dir / "out.obj").string()});
  expect_file_error(r, b);
  EXPECT_NE(r.err.find(".obj"), std::string::npos) << describe(r);
  EXPECT_FALSE(fs::exists(dir / "out.obj"));
}

TEST(Cli, NanCoordinateInObjIsAnError) {
  TempDir dir;
  const std::string a = put(dir, "a.obj", box_a());
  // Box B as OBJ text with the x coordinate of vertex 4 (line 4) replaced by "nan".
  const Mesh b = box_b();
  std::string text;
  for (std::size_t i = 0; i < b.vertices.size(); ++i) {
    const auto& p = b.vertices[i];
    text += "v " + (i == 3 ? std::string("nan") : std::to_string(p.x)) + " " + std::to_string(p.y) + " " +
            std::to_string(p.z) + "\n";
  }
  for (std::size_t f = 0; f < b.face_count(); ++f) {
    text += "f";
    for (std::uint32_t v : b.face(f)) {
      text += ' ';
      text += std::to_string(v + 1);
    }
    text += "\n";
  }
  write_file(dir / "b.obj", text);
  const RunResult r = run_cli(dir, {"union", a, (dir / "b.obj").string(), "-o", (dir / "out.obj").string()});
  expect_file_error(r, (dir / "b.obj").string());
  EXPECT_EQ(r.err.rfind("ember: " + (dir / "b.obj").string() + ":4:", 0), 0u) << "should name line 4\n" << describe(r);
  EXPECT_FALSE(fs::exists(dir / "out.obj"));
}

TEST(Cli, NanCoordinateInBinaryPlyIsAnError) {
  TempDir dir;
  const std::string a = put(dir, "a.obj", box_a());
  Mesh b = box_b();
  // The writers refuse NaN, so a marker value is written and patched into a
  // NaN in the binary PLY's doubles.
  const double marker = 12345.5, nan = std::nan("");
  b.vertices[3].y = marker;
  std::string bytes = ember::write_ply(b);
  const std::size_t at = bytes.find(std::string(reinterpret_cast<const char*>(&marker), 8));
  ASSERT_NE(at, std::string::npos);
  bytes.replace(at, 8, std::string(reinterpret_cast<const char*>(&nan), 8));
  const std::string bp = "b.ply";
  write_file(dir / bp, bytes);
  const RunResult r = run_cli(dir, {"union", a, bp, "-o", (dir / "out.obj").string()});
  expect_file_error(r, bp);
  EXPECT_TRUE(r.err.find("finite") != std::string::npos || r.err.find("NaN") != std::string::npos) << describe(r);
  EXPECT_FALSE(fs::exists(dir / "out.obj"));
}

TEST(Cli, OpenMeshIsAnErrorNamingFileAndAllowOpen) {
  TempDir dir;
  const std::string a = put(dir, "a.obj", box_b());
  const std::string open = put(dir, "open.obj", open_box());
  const fs::path out = dir / "out.obj";
  const RunResult r = run_cli(dir, {"union", a, open, "-o", out.string()});
  EXPECT_EQ(r.exit_code, 1) << describe(r);
  ASSERT_EQ(lines_of(r.err).size(), 1u) << describe(r);
  EXPECT_EQ(r.err.rfind("ember: " + open, 0), 0u) << describe(r);
  EXPECT_NE(r.err.find("--allow-open"), std::string::npos) << describe(r);
  EXPECT_EQ(r.err.find(a), std::string::npos) << "the closed input is not to blame\n" << describe(r);
  EXPECT_FALSE(fs::exists(out));
  EXPECT_EQ(dir.listing(), (std::set<std::string>{"a.obj", "open.obj"}));
}

TEST(Cli, OpenMeshErrorFollowsTheDocumentedFormat) {
  // README: "1 with a one-line `ember: <file>: <problem>` on stderr for any error".
  TempDir dir;
  const std::string a = put(dir, "a.obj", box_b());
  const std::string open = put(dir, "open.obj", open_box());
  const RunResult r = run_cli(dir, {"union", a, open, "-o", (dir / "out.obj").string()});
  expect_file_error(r, open);
}

TEST(Cli, OpenMeshAmongElevenInputsNamesTheRightFile) {
  // With 11 inputs the library reports "operand 10 ..."; the message must name
  // the 11th file, not the 2nd ("operand 1" is a prefix of "operand 10").
  TempDir dir;
  std::vector<std::string> args{"union"};
  for (int i = 0; i < 10; ++i)
    args.push_back(put(dir, "in" + std::to_string(i) + ".obj", box({double(i), 0, 0}, {i + 1.5, 1, 1})));
  const std::string open = put(dir, "last_open.obj", open_box());
  args.push_back(open);
  args.push_back("-o");
  args.push_back((dir / "out.obj").string());
  const RunResult r = run_cli(dir, args);
  EXPECT_EQ(r.exit_code, 1) << describe(r);
  EXPECT_NE(r.err.find(open), std::string::npos) << "should name " << open << "\n" << describe(r);
  EXPECT_EQ(r.err.find((dir / "in1.obj").string()), std::string::npos) << describe(r);
  EXPECT_FALSE(fs::exists(dir / "out.obj"));
}

TEST(Cli, AllowOpenWarnsAndSucceeds) {
  TempDir dir;
  const std::string a = put(dir, "a.obj", box_b());
  const std::string open = put(dir, "open.obj", open_box());
  const fs::path out = dir / "out.obj";
  const RunResult r = run_cli(dir, {"union", a, open, "-o", out.string(), "--allow-open"});
  ASSERT_EQ(r.exit_code, 0) << describe(r);
  const auto lines = lines_of(r.err);
  ASSERT_EQ(lines.size(), 1u) << "expected one warning line\n" << describe(r);
  EXPECT_EQ(lines[0].rfind("ember: warning: ", 0), 0u) << describe(r);
  EXPECT_NE(lines[0].find("not closed"), std::string::npos) << describe(r);
  const Mesh m = ember::read_mesh(out);
  EXPECT_GT(m.face_count(), 0u);
  EXPECT_EQ(dir.listing(), (std::set<std::string>{"a.obj", "open.obj", "out.obj"}));
}

TEST(Cli, AllowOpenWarningNamesTheFile) {
  // Errors name the file behind "operand i"; the --allow-open warning about the
  // same condition should too (a user does not know operand numbers).
  TempDir dir;
  const std::string a = put(dir, "a.obj", box_b());
  const std::string open = put(dir, "open.obj", open_box());
  const RunResult r = run_cli(dir, {"union", a, open, "-o", (dir / "out.obj").string(), "--allow-open"});
  ASSERT_EQ(r.exit_code, 0) << describe(r);
  EXPECT_NE(r.err.find(open), std::string::npos) << "the warning should name " << open << "\n" << describe(r);
}

TEST(Cli, UsageErrorsExitWithTwo) {
  TempDir dir;
  const std::string a = put(dir, "a.obj", box_a()), b = put(dir, "b.obj", box_b());
  const std::string out = (dir / "out.obj").string();
  // Only one input.
  expect_usage_error(run_cli(dir, {"union", a, "-o", out}));
  // No -o.
  expect_usage_error(run_cli(dir, {"union", a, b}));
  // -o without a value.
  expect_usage_error(run_cli(dir, {"difference", a, b, "-o"}));
  // Negative and non-numeric thread counts.
  expect_usage_error(run_cli(dir, {"union", a, b, "-o", out, "--threads", "-1"}));
  expect_usage_error(run_cli(dir, {"union", a, b, "-o", out, "--threads", "many"}));
  // Unknown option, unknown subcommand, no subcommand.
  expect_usage_error(run_cli(dir, {"union", a, b, "-o", out, "--frobnicate"}));
  expect_usage_error(run_cli(dir, {"merge", a, b, "-o", out}));
  expect_usage_error(run_cli(dir, {}));
  EXPECT_FALSE(fs::exists(out));
  EXPECT_EQ(dir.listing(), (std::set<std::string>{"a.obj", "b.obj"}));
}

TEST(Cli, FailedRunDoesNotClobberAnExistingOutput) {
  TempDir dir;
  const std::string a = put(dir, "a.obj", box_a());
  const std::string bad = (dir / "bad.off").string();
  write_file(bad, "OFF\n3 1 0\n0 0 0\n1 0 0\n");  // truncated: vertex and face missing
  const fs::path out = dir / "out.obj";
  const std::string sentinel = "# sentinel: must survive a failed run\n";
  write_file(out, sentinel);
  RunResult r = run_cli(dir, {"union", a, bad, "-o", out.string()});
  expect_file_error(r, bad);
  EXPECT_EQ(read_file(out), sentinel);
  // Also when the failure comes from the core (open input) and with --stats.
  const std::string open = put(dir, "open.obj", open_box());
  r = run_cli(dir, {"xor", a, open, "-o", out.string(), "--stats"});
  EXPECT_EQ(r.exit_code, 1) << describe(r);
  EXPECT_EQ(read_file(out), sentinel);
  EXPECT_EQ(dir.listing(), (std::set<std::string>{"a.obj", "bad.off", "open.obj", "out.obj"}));
}

TEST(Cli, SuccessfulRunReplacesAnExistingOutput) {
  TempDir dir;
  const std::string a = put(dir, "a.obj", box_a()), b = put(dir, "b.obj", box_b());
  const fs::path out = dir / "out.obj";
  write_file(out, "# old content\n");
  const RunResult r = run_cli(dir, {"intersection", a, b, "-o", out.string()});
  ASSERT_EQ(r.exit_code, 0) << describe(r);
  EXPECT_EQ(volume(read_result(out)), 1);
  EXPECT_EQ(dir.listing(), (std::set<std::string>{"a.obj", "b.obj", "out.obj"}));
}

TEST(Cli, UnwritableOutputDirectoryIsAnError) {
  TempDir dir;
  const std::string a = put(dir, "a.obj", box_a()), b = put(dir, "b.obj", box_b());
  const std::string out = (dir / "missing_dir" / "out.obj").string();
  const RunResult r = run_cli(dir, {"union", a, b, "-o", out});
  expect_file_error(r, out);
  EXPECT_FALSE(fs::exists(dir / "missing_dir"));
  EXPECT_EQ(dir.listing(), (std::set<std::string>{"a.obj", "b.obj"}));
}

TEST(Cli, OutputIntoADirectoryPathFailsWithoutLeftovers) {
  // -o names an existing directory: the rename cannot replace it; the
  // temporary file must be cleaned up and the directory left alone.
  TempDir dir;
  const std::string a = put(dir, "a.obj", box_a()), b = put(dir, "b.obj", box_b());
  fs::create_directories(dir / "res.obj");
  const std::string out = (dir / "res.obj").string();
  const RunResult r = run_cli(dir, {"union", a, b, "-o", out});
  expect_file_error(r, out);
  EXPECT_TRUE(fs::is_directory(dir / "res.obj"));
  EXPECT_TRUE(fs::is_empty(dir / "res.obj"));
  EXPECT_EQ(dir.listing(), (std::set<std::string>{"a.obj", "b.obj", "res.obj"}));
}

// ---- empty results -----------------------------------------------------------------

TEST(Cli, EmptyResultWritesAValidEmptyMeshInEveryFormat) {
  TempDir dir;
  const std::string inner = put(dir, "inner.obj", box({1, 1, 1}, {2, 2, 2}));
  const std::string outer = put(dir, "outer.obj", box({0, 0, 0}, {3, 3, 3}));
  for (const char* ext : {"obj", "stl", "ply", "off"}) {
    SCOPED_TRACE(ext);
    const fs::path out = dir / (std::string("empty.") + ext);
    const RunResult r = run_cli(dir, {"difference", inner, outer, "-o", out.string(), "--stats"});
    ASSERT_EQ(r.exit_code, 0) << describe(r);
    EXPECT_EQ(json_number(r.err, "output_polygons"), 0) << describe(r);
    ASSERT_TRUE(fs::exists(out));
    Mesh m;
    ASSERT_NO_THROW(m = ember::read_mesh(out)) << read_file(out);
    EXPECT_EQ(m.face_count(), 0u);
  }
  // Disjoint inputs: the intersection is empty too.
  const std::string far = put(dir, "far.obj", box({10, 10, 10}, {11, 11, 11}));
  const RunResult r = run_cli(dir, {"intersection", inner, far, "-o", (dir / "none.obj").string()});
  ASSERT_EQ(r.exit_code, 0) << describe(r);
  EXPECT_EQ(ember::read_mesh(dir / "none.obj").face_count(), 0u);
}

// ---- demo and help -------------------------------------------------------------------

TEST(Cli, DemoWritesConsistentBooleans) {
  TempDir dir;
  const fs::path demo = dir / "demo out";
  const RunResult r = run_cli(dir, {"demo", "-o", demo.string(), "--threads", "2"});
  ASSERT_EQ(r.exit_code, 0) << describe(r);
  std::map<std::string, Mesh> m;
  for (const char* name : {"torus", "sphere", "union", "intersection", "difference"}) {
    const fs::path p = demo / (std::string(name) + ".obj");
    ASSERT_TRUE(fs::exists(p)) << p;
    m[name] = ember::read_mesh(p);
    EXPECT_GT(m[name].face_count(), 0u) << name;
    EXPECT_EQ(ember::test::face_problems(m[name]), "") << name;
  }
  // Exactly the five meshes, no temporaries.
  std::set<std::string> files;
  for (const auto& e : fs::directory_iterator(demo)) files.insert(e.path().filename().string());
  EXPECT_EQ(files,
            (std::set<std::string>{"torus.obj", "sphere.obj", "union.obj", "intersection.obj", "difference.obj"}));
  EXPECT_TRUE(ember::test::closed_oriented(m["torus"]));
  EXPECT_TRUE(ember::test::closed_oriented(m["sphere"]));
  const double vt = volume(m["torus"]), vs = volume(m["sphere"]);
  const double vu = volume(m["union"]), vi = volume(m["intersection"]), vd = volume(m["difference"]);
  EXPECT_GT(vi, 0);
  EXPECT_LT(vi, std::min(vt, vs));
  EXPECT_GT(vu, std::max(vt, vs));
  EXPECT_TRUE(ember::test::close_rel(vu + vi, vt + vs, 1e-6)) << vu + vi << " vs " << vt + vs;
  EXPECT_TRUE(ember::test::close_rel(vd + vi, vt, 1e-6)) << vd + vi << " vs " << vt;
  // The report on stdout mentions each operation and file.
  for (const char* op : {"union", "intersection", "difference"}) EXPECT_NE(r.out.find(op), std::string::npos) << op;
}

TEST(Cli, DemoDefaultDirectory) {
  TempDir dir;
  const RunResult r = run_cli(dir, {"demo", "--threads", "1"});
  ASSERT_EQ(r.exit_code, 0) << describe(r);
  for (const char* name : {"torus", "sphere", "union", "intersection", "difference"})
    EXPECT_TRUE(fs::exists(dir / "ember-demo" / (std::string(name) + ".obj"))) << name;
}

TEST(Cli, HelpMentionsEverySubcommand) {
  TempDir dir;
  const RunResult r = run_cli(dir, {"--help"});
  ASSERT_EQ(r.exit_code, 0) << describe(r);
  for (const char* sub : {"union", "intersection", "difference", "xor", "demo"})
    EXPECT_NE(r.out.find(sub), std::string::npos) << sub << "\n" << describe(r);
  // Subcommand help lists the options.
  const RunResult u = run_cli(dir, {"union", "--help"});
  ASSERT_EQ(u.exit_code, 0) << describe(u);
  for (const char* opt :
       {"--min-k", "--threads", "--stats", "--allow-open", "--assume-solid", "--no-solid-check", "-o"})
    EXPECT_NE(u.out.find(opt), std::string::npos) << opt << "\n" << describe(u);
}

}  // namespace
