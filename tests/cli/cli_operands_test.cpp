// At the command line: operands are counted by object, not by file; every
// format's empty mesh is refused as an operand; a replaced output keeps its
// mode and a read-only one is refused; out of memory is reported as such.
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cstring>
#include <string>
#include <vector>

#include "ember/io/mesh_io.hpp"
#include "support/cli_harness.hpp"
#include "support/shapes.hpp"

namespace {

using namespace ember::clitest;
using ember::Mesh;
using ember::test::box;

bool has(const std::string& s, const std::string& part) { return s.find(part) != std::string::npos; }

/// two.3mf: [0,2]^3 and [1,3]^3 as two objects (two operands) of one file.
void write_two_object_3mf(const TempDir& dir) {
  const std::vector<Mesh> meshes{box({0, 0, 0}, {2, 2, 2}), box({1, 1, 1}, {3, 3, 3})};
  write_file(dir / "two.3mf", ember::write_3mf(meshes));
}

TEST(CliOperands, OneThreeMfFileWithTwoObjectsIsTwoOperands) {
  TempDir dir;
  write_two_object_3mf(dir);
  RunResult r = run_cli(dir, {"intersection", "two.3mf", "-o", "o.obj"});
  ASSERT_EQ(r.exit_code, 0) << describe(r);
  EXPECT_GT(ember::read_mesh(dir / "o.obj").face_count(), 0u);
  r = run_cli(dir, {"union", "two.3mf", "--min-k", "2", "-o", "k.obj"});
  ASSERT_EQ(r.exit_code, 0) << describe(r);
  // --min-k's range is the operand count (2 here), not the file count (1).
  r = run_cli(dir, {"union", "two.3mf", "--min-k", "3", "-o", "k3.obj"});
  EXPECT_EQ(r.exit_code, 2) << describe(r);
  EXPECT_TRUE(has(r.err, "--min-k: '3' is out of range; accepted: K from 1 to the number of operands (2)"))
      << describe(r);
  // With the 3MF file and one more file: three operands.
  ember::write_mesh(box({0.5, 0.5, 0.5}, {2.5, 2.5, 2.5}), dir / "c.obj");
  r = run_cli(dir, {"union", "two.3mf", "c.obj", "--min-k", "3", "-o", "k3.obj"});
  EXPECT_EQ(r.exit_code, 0) << describe(r);
}

TEST(CliOperands, ThreeMfExpansionLimitIsAnOption) {
  TempDir dir;
  write_two_object_3mf(dir);  // 2 x 12 triangles
  RunResult r = run_cli(dir, {"union", "two.3mf", "-o", "o.obj", "--max-3mf-triangles", "20"});
  EXPECT_EQ(r.exit_code, 1) << describe(r);
  EXPECT_TRUE(has(r.err, "ember: two.3mf: 3MF: the build items expand to 24 triangles")) << describe(r);
  EXPECT_TRUE(has(r.err, "--max-3mf-triangles")) << describe(r);
  EXPECT_FALSE(fs::exists(dir / "o.obj"));
  r = run_cli(dir, {"union", "two.3mf", "-o", "o.obj", "--max-3mf-triangles", "24", "--max-3mf-instancing", "1"});
  EXPECT_EQ(r.exit_code, 0) << describe(r);
  for (const char* bad : {"0", "x", "-5", "99999999999999999999999"}) {
    r = run_cli(dir, {"union", "two.3mf", "-o", "o2.obj", "--max-3mf-triangles", bad});
    EXPECT_EQ(r.exit_code, 2) << describe(r);
    EXPECT_TRUE(has(r.err, "--max-3mf-triangles: '" + std::string(bad) + "'")) << describe(r);
  }
}

TEST(CliOperands, FewerThanTwoOperandsIsAUsageError) {
  TempDir dir;
  ember::write_mesh(box({0, 0, 0}, {1, 1, 1}), dir / "a.obj");
  ember::write_mesh(box({0, 0, 0}, {1, 1, 1}), dir / "one.3mf");
  for (const char* in : {"a.obj", "one.3mf"}) {
    SCOPED_TRACE(in);
    const RunResult r = run_cli(dir, {"union", in, "-o", "o.obj"});
    EXPECT_EQ(r.exit_code, 2) << describe(r);
    EXPECT_TRUE(has(r.err, "at least 2 operands are required, but '" + std::string(in) + "' holds 1")) << describe(r);
    EXPECT_FALSE(fs::exists(dir / "o.obj"));
  }
}

TEST(CliOperands, AnOperandWithoutFacesIsAnErrorInEveryFormat) {
  TempDir dir;
  ember::write_mesh(box({0, 0, 0}, {1, 1, 1}), dir / "b.obj");
  const Mesh empty;
  for (const char* name : {"e.ply", "e.off", "e.stl", "e.3mf", "e.obj"}) {
    SCOPED_TRACE(name);
    ember::write_mesh(empty, dir / name);  // a valid file of that format with zero faces
    const RunResult r = run_cli(dir, {"union", name, "b.obj", "-o", "o.obj"});
    EXPECT_EQ(r.exit_code, 1) << describe(r);
    EXPECT_TRUE(has(r.err, "ember: " + std::string(name) + ": has no faces (an empty mesh)")) << describe(r);
    EXPECT_FALSE(fs::exists(dir / "o.obj"));
  }
  // A 3MF object without triangles beside one with triangles is named by its object.
  write_file(dir / "mixed.3mf", ember::write_3mf(std::vector<Mesh>{box({0, 0, 0}, {1, 1, 1}), empty}));
  const RunResult r = run_cli(dir, {"union", "mixed.3mf", "b.obj", "-o", "o.obj"});
  EXPECT_EQ(r.exit_code, 1) << describe(r);
  EXPECT_TRUE(has(r.err, "ember: mixed.3mf (object 2 of 2): has no faces")) << describe(r);
}

TEST(CliOutputFile, ReplacedOutputKeepsItsMode) {
  TempDir dir;
  ember::write_mesh(box({0, 0, 0}, {2, 2, 2}), dir / "a.obj");
  ember::write_mesh(box({1, 1, 1}, {3, 3, 3}), dir / "b.obj");
  for (const mode_t mode : {mode_t{0600}, mode_t{0640}, mode_t{0755}}) {
    SCOPED_TRACE(mode);
    write_file(dir / "out.obj", "old\n");
    ASSERT_EQ(::chmod((dir / "out.obj").c_str(), mode), 0);
    const RunResult r = run_cli(dir, {"union", "a.obj", "b.obj", "-o", "out.obj"});
    ASSERT_EQ(r.exit_code, 0) << describe(r);
    struct stat st {};
    ASSERT_EQ(::stat((dir / "out.obj").c_str(), &st), 0);
    EXPECT_EQ(st.st_mode & 07777, mode);
    EXPECT_NE(read_file(dir / "out.obj"), "old\n");
  }
}

TEST(CliOutputFile, ReadOnlyOutputIsRefused) {
  TempDir dir;
  ember::write_mesh(box({0, 0, 0}, {2, 2, 2}), dir / "a.obj");
  ember::write_mesh(box({1, 1, 1}, {3, 3, 3}), dir / "b.obj");
  write_file(dir / "out.obj", "precious\n");
  ASSERT_EQ(::chmod((dir / "out.obj").c_str(), 0444), 0);
  const RunResult r = run_cli(dir, {"union", "a.obj", "b.obj", "-o", "out.obj"});
  EXPECT_EQ(r.exit_code, 1) << describe(r);
  EXPECT_TRUE(has(r.err, "ember: out.obj: exists and is read-only")) << describe(r);
  EXPECT_EQ(read_file(dir / "out.obj"), "precious\n");
  EXPECT_EQ(dir.listing(), (std::set<std::string>{"a.obj", "b.obj", "out.obj"}));
}

#if defined(__SANITIZE_ADDRESS__)
#define EMBER_TEST_ASAN 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define EMBER_TEST_ASAN 1
#endif
#endif

/// Runs `ember ARGS` in dir under a 1 GB address-space limit; checks it
/// exits with 1 and writes no o.obj, and returns its stderr.
[[maybe_unused]] std::string run_under_memory_limit(const TempDir& dir, const std::string& args) {
  const std::string cmd = "cd " + shell_quote(dir.work().string()) + " && ulimit -v 1000000 && " +
                          shell_quote(cli_path()) + " " + args + " 2>" + shell_quote((dir.io() / "err.txt").string());
  const int status = std::system(cmd.c_str());
  EXPECT_TRUE(WIFEXITED(status));
  EXPECT_EQ(WEXITSTATUS(status), 1);
  EXPECT_FALSE(fs::exists(dir / "o.obj"));
  return read_file(dir.io() / "err.txt");
}

TEST(CliErrors, OutOfMemoryWhileReadingSaysSo) {
#ifdef EMBER_TEST_ASAN
  GTEST_SKIP() << "AddressSanitizer reserves more address space than the limit this test sets";
#else
  TempDir dir;
  ember::write_mesh(box({0, 0, 0}, {1, 1, 1}), dir / "b.obj");
  // A sparse binary STL of 60 million (zero) triangles: 3 GB that take no
  // disk space, and more memory than the 1 GB limit below allows.
  const std::uint32_t n = 60'000'000;
  std::string header(84, '\0');
  std::memcpy(header.data() + 80, &n, 4);
  write_file(dir / "big.stl", header);
  ASSERT_EQ(::truncate((dir / "big.stl").c_str(), 84 + std::int64_t{50} * n), 0);
  const std::string err = run_under_memory_limit(dir, "union big.stl b.obj -o o.obj");
  EXPECT_TRUE(has(err, "ember: out of memory while reading big.stl")) << err;
  EXPECT_FALSE(has(err, "unexpected error")) << err;
#endif
}

TEST(CliErrors, OutOfMemoryDuringTheBooleanSaysSo) {
#ifdef EMBER_TEST_ASAN
  GTEST_SKIP() << "AddressSanitizer reserves more address space than the limit this test sets";
#else
  TempDir dir;
  // Two combs of 600 thin slabs each, crossing at right angles: 14,400 input
  // triangles whose union has 360,000 crossings, far more than 1 GB of
  // memory holds (unlimited, it passes 1.7 GB), while reading them takes
  // little.
  const auto comb = [](int axis) {
    std::vector<ember::Mesh> slabs;
    for (int i = 0; i < 600; ++i) {
      ember::Vec3d lo{0, 0, 0}, hi{600, 600, 1};
      (axis == 0 ? lo.x : lo.y) = i + 0.25;
      (axis == 0 ? hi.x : hi.y) = i + 0.75;
      slabs.push_back(ember::test::box(lo, hi));
    }
    return ember::test::merge(slabs);
  };
  ember::write_mesh(comb(0), dir / "a.obj");
  ember::write_mesh(comb(1), dir / "b.obj");
  const std::string err = run_under_memory_limit(dir, "union a.obj b.obj -o o.obj --threads 2");
  EXPECT_TRUE(has(err, "ember: out of memory while computing the Boolean of 14400 triangles")) << err;
  EXPECT_FALSE(has(err, "unexpected error")) << err;
#endif
}

}  // namespace
