// At the command line: no silent wrong result (grid errors and
// warnings), the private temporary output file, system reasons in errors,
// usage errors with ranges, --version, reader tolerance and the solid check's
// reasons in --stats.
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/stat.h>

#include <regex>
#include <string>

#include "support/cli_harness.hpp"
#include "ember/io/mesh_io.hpp"
#include "support/mesh_checks.hpp"
#include "support/shapes.hpp"

namespace {

using namespace ember::clitest;
using ember::Mesh;
using ember::test::box;

std::string write_input(const TempDir& dir, const std::string& name, const Mesh& m) {
  ember::write_mesh(m, dir / name);
  return name;
}

/// a.obj = [0,2]^3 and b.obj = [1,3]^3 in the test folder.
void write_two_boxes(const TempDir& dir) {
  write_input(dir, "a.obj", box({0, 0, 0}, {2, 2, 2}));
  write_input(dir, "b.obj", box({1, 1, 1}, {3, 3, 3}));
}

bool has(const std::string& s, const std::string& part) { return s.find(part) != std::string::npos; }

/// The raw text of a key's value in the --stats line ("" if missing).
std::string stats_value(const std::string& err, const std::string& key) {
  const std::regex re("\"" + key + "\": (\"[^\"]*\"|[-0-9.eE+]+)");
  std::smatch m;
  return std::regex_search(err, m, re) ? m[1].str() : "";
}

// ---- items 1-3: the grid ---------------------------------------------------------

TEST(CliGrid, OperandLostOnTheGridIsAnErrorAndNoOutput) {
  TempDir dir;
  const std::string cube = write_input(dir, "cube.obj", box({0, 0, 0}, {1, 1, 1}));
  const std::string slab = write_input(dir, "slab.obj", box({-1e30, -1e30, 0.5}, {1e30, 1e30, 1e30}));
  const RunResult r = run_cli(dir, {"difference", cube, slab, "-o", "out.obj"});
  EXPECT_EQ(r.exit_code, 1) << describe(r);
  ASSERT_EQ(lines_of(r.err).size(), 1u) << describe(r);
  EXPECT_TRUE(has(r.err, "ember: cube.obj: 12 of its 12 triangles collapse")) << describe(r);
  EXPECT_TRUE(has(r.err, "step 3.78e+22")) << describe(r);
  EXPECT_FALSE(fs::exists(dir / "out.obj"));
}

TEST(CliGrid, ManifoldCrayPairIsAnErrorNotAnEmptyResult) {
  // Cray_right is a +-3.4e38 box: on the joint grid Cray_left vanishes.
  const fs::path data = EMBER_SHARED_DATA_DIR "/peer-tests/manifold";
  if (!fs::exists(data / "Cray_left.obj") || !fs::exists(data / "Cray_right.obj"))
    GTEST_SKIP() << "real meshes not found under " << data << " (../shared/data beside the checkout)";
  TempDir dir;
  const RunResult r = run_cli(
      dir, {"difference", (data / "Cray_left.obj").string(), (data / "Cray_right.obj").string(), "-o", "out.obj"});
  EXPECT_EQ(r.exit_code, 1) << describe(r);
  EXPECT_TRUE(has(r.err, "Cray_left.obj: 576 of its 576 triangles collapse")) << describe(r);
  EXPECT_FALSE(fs::exists(dir / "out.obj"));
}

TEST(CliGrid, SubGridFeatureWarnsAndCountsInStats) {
  TempDir dir;
  const Mesh a = ember::test::merge(
      {ember::test::icosphere({0, 0, 0}, 1.0, 3), box({0.1, 0.1, 0.1}, {0.1 + 1e-9, 0.1 + 1e-9, 0.1 + 1e-9})});
  const std::string in_a = write_input(dir, "a.obj", a), in_b = write_input(dir, "b.obj", box({0, 0, 0}, {2, 2, 2}));
  const RunResult r = run_cli(dir, {"union", in_a, in_b, "-o", "out.obj", "--stats"});
  ASSERT_EQ(r.exit_code, 0) << describe(r);
  EXPECT_TRUE(has(r.err, "ember: warning: a.obj: 12 of its")) << describe(r);
  EXPECT_TRUE(has(r.err, "collapse and 0 flip on the quantization grid (step 5.96e-08")) << describe(r);
  EXPECT_EQ(stats_value(r.err, "collapsed_triangles"), "12") << describe(r);
  EXPECT_EQ(stats_value(r.err, "flipped_triangles"), "0") << describe(r);
  EXPECT_EQ(stats_value(r.err, "grid_step"), "5.9604644775390625e-08") << describe(r);
}

TEST(CliGrid, SubnormalRangeInputIsRefused) {
  TempDir dir;
  const Mesh tiny = ember::test::scale(box({0, 0, 0}, {1, 1, 1}), 1e-305);
  const std::string a = write_input(dir, "a.obj", tiny), b = write_input(dir, "b.obj", tiny);
  const RunResult r = run_cli(dir, {"union", a, b, "-o", "out.obj"});
  EXPECT_EQ(r.exit_code, 1) << describe(r);
  EXPECT_TRUE(has(r.err, "coordinates too small to quantize")) << describe(r);
  EXPECT_FALSE(fs::exists(dir / "out.obj"));
}

// ---- the temporary output file --------------------------------------------

TEST(CliOutputFile, PlantedSymlinkAtTheOldTemporaryNameIsNotFollowed) {
  TempDir dir;
  write_two_boxes(dir);
  const std::string a = "a.obj", b = "b.obj";
  write_file(dir / "victim.txt", "precious\n");
  fs::create_symlink("victim.txt", dir / "out.obj.ember-tmp");
  const RunResult r = run_cli(dir, {"union", a, b, "-o", "out.obj"});
  ASSERT_EQ(r.exit_code, 0) << describe(r);
  EXPECT_EQ(read_file(dir / "victim.txt"), "precious\n");
  EXPECT_TRUE(fs::is_symlink(dir / "out.obj.ember-tmp"));
  EXPECT_TRUE(fs::is_regular_file(fs::symlink_status(dir / "out.obj")));
  EXPECT_EQ(dir.listing(), (std::set<std::string>{"a.obj", "b.obj", "out.obj", "out.obj.ember-tmp", "victim.txt"}));
}

TEST(CliOutputFile, OutputThatIsASymlinkIsRefused) {
  TempDir dir;
  write_two_boxes(dir);
  const std::string a = "a.obj", b = "b.obj";
  write_file(dir / "victim.obj", "precious\n");
  fs::create_symlink("victim.obj", dir / "out.obj");
  const RunResult r = run_cli(dir, {"union", a, b, "-o", "out.obj"});
  EXPECT_EQ(r.exit_code, 1) << describe(r);
  EXPECT_TRUE(has(r.err, "ember: out.obj: exists and is a symbolic link, not a regular file; refusing")) << describe(r);
  EXPECT_TRUE(fs::is_symlink(dir / "out.obj"));
  EXPECT_EQ(read_file(dir / "victim.obj"), "precious\n");
  EXPECT_EQ(dir.listing(), (std::set<std::string>{"a.obj", "b.obj", "out.obj", "victim.obj"}));
}

TEST(CliOutputFile, NewOutputGetsTheModeFromTheUmask) {
  TempDir dir;
  write_two_boxes(dir);
  const std::string a = "a.obj", b = "b.obj";
  for (const mode_t mask : {mode_t{022}, mode_t{027}}) {
    fs::remove(dir / "out.obj");       // a new file (a replaced one keeps its mode)
    const mode_t old = ::umask(mask);  // inherited by the CLI's process
    const RunResult r = run_cli(dir, {"union", a, b, "-o", "out.obj"});
    ::umask(old);
    ASSERT_EQ(r.exit_code, 0) << describe(r);
    struct stat st {};
    ASSERT_EQ(::stat((dir / "out.obj").c_str(), &st), 0);
    EXPECT_EQ(st.st_mode & 0777, 0666 & ~mask);
  }
}

TEST(CliOutputFile, SignalWhileTheTemporaryFileExistsRemovesIt) {
  TempDir dir;
  write_two_boxes(dir);
  const std::string a = "a.obj", b = "b.obj";
  for (const char* sig : {"TERM", "INT", "HUP", "QUIT"}) {
    SCOPED_TRACE(sig);
    // EMBER_TEST_HOLD_TEMP_MS keeps the finished temporary file for 20 s
    // before the rename; the signal arrives while it is held.
    // ulimit -c 0: SIGQUIT's default action would leave a core file.
    std::string cmd = "cd " + shell_quote(dir.work().string()) + " && (ulimit -c 0; EMBER_TEST_HOLD_TEMP_MS=20000 " +
                      shell_quote(cli_path()) + " union a.obj b.obj -o out.obj & pid=$!; " +
                      "for i in $(seq 100); do ls -a | grep -q ember- && break; sleep 0.1; done; " +
                      "ls -a | grep -c ember- > " + shell_quote((dir.io() / "seen.txt").string()) + "; kill -" + sig +
                      " $pid; wait $pid; echo $? > " + shell_quote((dir.io() / "rc.txt").string()) + ")";
    ASSERT_EQ(std::system(cmd.c_str()), 0) << cmd;
    EXPECT_EQ(read_file(dir.io() / "seen.txt"), "1\n") << "the temporary file was never seen";
    EXPECT_NE(read_file(dir.io() / "rc.txt"), "0\n");
    EXPECT_EQ(dir.listing(), (std::set<std::string>{"a.obj", "b.obj"}));
  }
}

// ---- items 5-6: empty OBJ, system reasons ------------------------------------------

TEST(CliErrors, EmptyObjIsNoFacesError) {
  TempDir dir;
  write_file(dir / "empty.obj", "");
  const std::string b = write_input(dir, "b.obj", box({1, 1, 1}, {3, 3, 3}));
  const RunResult r = run_cli(dir, {"union", "empty.obj", b, "-o", "out.obj"});
  EXPECT_EQ(r.exit_code, 1) << describe(r);
  EXPECT_TRUE(has(r.err, "ember: empty.obj: empty file: no faces in empty.obj")) << describe(r);
  EXPECT_FALSE(fs::exists(dir / "out.obj"));
}

TEST(CliErrors, SystemErrorsCarryTheSystemReason) {
  TempDir dir;
  write_two_boxes(dir);
  const std::string a = "a.obj", b = "b.obj";
  RunResult r = run_cli(dir, {"union", a, b, "-o", "nodir/out.obj"});
  EXPECT_EQ(r.exit_code, 1) << describe(r);
  EXPECT_EQ(r.err, "ember: nodir/out.obj: cannot open for writing: No such file or directory\n") << describe(r);
  // A file where the folder should be.
  write_file(dir / "plain", "x");
  r = run_cli(dir, {"union", a, b, "-o", "plain/out.obj"});
  EXPECT_EQ(r.err, "ember: plain/out.obj: cannot open for writing: Not a directory\n") << describe(r);
  EXPECT_EQ(dir.listing(), (std::set<std::string>{"a.obj", "b.obj", "plain"}));
}

// ---- usage errors and --version ---------------------------------------------

TEST(CliUsage, BadValuesNameTheOptionAndTheAcceptedRange) {
  TempDir dir;
  write_two_boxes(dir);
  const std::string a = "a.obj", b = "b.obj";
  struct Case {
    std::vector<std::string> args;
    std::string message;
  };
  const std::vector<Case> cases = {
      {{"union", a, b, "-o", "o.obj", "--min-k", "3"},
       "ember: --min-k: '3' is out of range; accepted: K from 1 to the number of operands (2)"},
      {{"union", a, b, "-o", "o.obj", "--min-k", "0"}, "--min-k: '0' is out of range; accepted: K from 1 to"},
      {{"union", a, b, "-o", "o.obj", "--min-k", "two"}, "--min-k: 'two' is not a whole number; accepted: K from 1"},
      {{"xor", a, b, "-o", "o.obj", "--min-k", "1"}, "--min-k applies to 'union' only"},
      {{"union", a, b, "-o", "o.obj", "--threads", "-1"},
       "--threads: '-1' is out of range; accepted: 0 (all cores) or a number of threads up to 65536"},
      {{"union", a, b, "-o", "o.obj", "--threads", "1e3"}, "--threads: '1e3' is not a whole number"},
      {{"demo", "-o", "d", "--threads", "99999999999999999999"}, "--threads: '99999999999999999999' is out of range"},
  };
  for (const Case& c : cases) {
    const RunResult r = run_cli(dir, c.args);
    EXPECT_EQ(r.exit_code, 2) << describe(r);
    EXPECT_EQ(lines_of(r.err).size(), 1u) << describe(r);
    EXPECT_TRUE(has(r.err, c.message)) << "expected: " << c.message << "\n" << describe(r);
  }
  EXPECT_EQ(dir.listing(), (std::set<std::string>{"a.obj", "b.obj"}));
}

TEST(CliUsage, VersionFlagAndStatsField) {
  TempDir dir;
  RunResult r = run_cli(dir, {"--version"});
  EXPECT_EQ(r.exit_code, 0) << describe(r);
  EXPECT_EQ(r.out, std::string("ember ") + EMBER_VERSION_FOR_TESTS + "\n") << describe(r);
  write_two_boxes(dir);
  const std::string a = "a.obj", b = "b.obj";
  r = run_cli(dir, {"union", a, b, "-o", "o.obj", "--stats"});
  ASSERT_EQ(r.exit_code, 0) << describe(r);
  EXPECT_EQ(stats_value(r.err, "version"), std::string("\"") + EMBER_VERSION_FOR_TESTS + "\"") << describe(r);
}

// ---- reader tolerance ------------------------------------------------------

TEST(CliReaders, ByteOrderMarkAndStlWithoutEndsolid) {
  TempDir dir;
  write_file(dir / "a.obj", "\xEF\xBB\xBF" + ember::write_obj(box({0, 0, 0}, {2, 2, 2})));
  std::string stl;
  const Mesh b = box({1, 1, 1}, {3, 3, 3});
  stl = "solid b\n";
  for (std::size_t f = 0; f < b.face_count(); ++f) {
    stl += "facet normal 0 0 0\nouter loop\n";
    for (const std::uint32_t v : b.face(f))
      stl += "vertex " + std::to_string(b.vertices[v].x) + " " + std::to_string(b.vertices[v].y) + " " +
             std::to_string(b.vertices[v].z) + "\n";
    stl += "endloop\nendfacet\n";
  }
  write_file(dir / "b.stl", stl);  // no endsolid
  const RunResult r = run_cli(dir, {"intersection", "a.obj", "b.stl", "-o", "o.obj"});
  ASSERT_EQ(r.exit_code, 0) << describe(r);
  EXPECT_TRUE(has(r.err, "ember: warning: b.stl: ASCII STL ends without 'endsolid'")) << describe(r);
  EXPECT_EQ(ember::test::volume(ember::read_mesh(dir / "o.obj")), 1);
}

// ---- why an operand is not solid -------------------------------------------

TEST(CliSolidCheck, StatsAndWarningSayWhyAnOperandIsNotSolid) {
  TempDir dir;
  const std::string self =
      write_input(dir, "self.obj", ember::test::self_intersecting_pair({0, 0, 0}, {2, 2, 2}, {1, 1, 1}, {3, 3, 3}));
  const std::string inv = write_input(dir, "inv.obj", ember::test::reverse_orientation(box({5, 5, 5}, {6, 6, 6})));
  const std::string ok = write_input(dir, "ok.obj", box({0, 0, 0}, {1, 1, 1}));
  const RunResult r = run_cli(dir, {"union", self, inv, ok, "-o", "o.obj", "--stats"});
  ASSERT_EQ(r.exit_code, 0) << describe(r);
  EXPECT_TRUE(has(r.err, "ember: warning: self.obj: not solid: self-intersecting (")) << describe(r);
  EXPECT_TRUE(has(r.err, "ember: warning: inv.obj: not solid: inconsistent orientation (1 components")) << describe(r);
  EXPECT_EQ(stats_value(r.err, "misoriented_components"), "1") << describe(r);
  EXPECT_GT(std::stoi(stats_value(r.err, "self_intersecting_pairs")), 0) << describe(r);
  EXPECT_EQ(stats_value(r.err, "self_intersecting_pairs_complete"), "1") << describe(r);  // an exact count
  EXPECT_EQ(stats_value(r.err, "open_edges"), "0") << describe(r);
  EXPECT_EQ(stats_value(r.err, "dropped_slivers"), "0") << describe(r);
  EXPECT_EQ(stats_value(r.err, "solid_operands"), "1") << describe(r);
  const std::string check = stats_value(r.err, "solid_check");
  EXPECT_TRUE(has(check, "self.obj: not solid: self-intersecting")) << check;
  EXPECT_TRUE(has(check, "ok.obj: proven solid")) << check;
}

}  // namespace

// ---- concave OBJ n-gons pass the solid check -------------------------------

TEST(CliSolidCheck, ConcaveObjPolygonsAreTriangulatedBeforeTheProof) {
  TempDir dir;
  // An L-shaped prism whose caps are single concave hexagons.
  write_file(dir / "l.obj",
             "v 0 0 0\nv 3 0 0\nv 3 1 0\nv 1 1 0\nv 1 3 0\nv 0 3 0\n"
             "v 0 0 1\nv 3 0 1\nv 3 1 1\nv 1 1 1\nv 1 3 1\nv 0 3 1\n"
             "f 6 5 4 3 2 1\nf 7 8 9 10 11 12\n"
             "f 1 2 8 7\nf 2 3 9 8\nf 3 4 10 9\nf 4 5 11 10\nf 5 6 12 11\nf 6 1 7 12\n");
  write_input(dir, "b.obj", box({2, 0, 0}, {4, 1, 1}));
  const RunResult r = run_cli(dir, {"union", "l.obj", "b.obj", "-o", "o.obj", "--stats"});
  ASSERT_EQ(r.exit_code, 0) << describe(r);
  EXPECT_EQ(lines_of(r.err).size(), 1u) << "no warnings expected\n" << describe(r);
  EXPECT_EQ(stats_value(r.err, "solid_operands"), "2") << describe(r);
  EXPECT_TRUE(has(stats_value(r.err, "solid_check"), "l.obj: proven solid")) << describe(r);
  EXPECT_EQ(ember::test::volume(ember::read_mesh(dir / "o.obj")), 6);
}
