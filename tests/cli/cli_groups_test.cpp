// Materials through the CLI: OBJ `usemtl` groups reach the output file.
#include <gtest/gtest.h>

#include <string>

#include "ember/io/mesh_io.hpp"
#include "support/cli_harness.hpp"
#include "support/shapes.hpp"

namespace {

using namespace ember::clitest;

TEST(CliFaceGroups, ObjMaterialsSurviveABoolean) {
  TempDir dir;
  ember::Mesh a = ember::test::box({0, 0, 0}, {2, 2, 2}), b = ember::test::box({1, 1, 1}, {3, 3, 3});
  a.face_groups.assign(a.face_count(), 0);
  a.group_names = {"red"};
  b.face_groups.assign(b.face_count(), 0);
  b.group_names = {"blue"};
  ember::write_mesh(a, dir / "a.obj");
  ember::write_mesh(b, dir / "b.obj");
  for (const std::string& command : {std::string("union"), std::string("difference")}) {
    const RunResult r = run_cli(dir, {command, "a.obj", "b.obj", "-o", "out.obj"});
    ASSERT_EQ(r.exit_code, 0) << describe(r);
    const ember::Mesh out = ember::read_mesh(dir / "out.obj");
    EXPECT_EQ(out.group_names, (std::vector<std::string>{"red", "blue"})) << command;
    ASSERT_EQ(out.face_groups.size(), out.face_count());
    // The difference's cut faces lie on b's faces: blue; a's remaining faces red.
    std::size_t blue = 0;
    for (const std::uint32_t g : out.face_groups) blue += g == 1;
    EXPECT_GT(blue, 0u) << command;
    EXPECT_LT(blue, out.face_count()) << command;
  }
}

}  // namespace
