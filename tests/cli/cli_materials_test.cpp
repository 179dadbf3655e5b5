// Materials through the CLI: OBJ `usemtl` and glTF materials reach the
// output file, and the result reads back closed with the exact volume.
#include <gtest/gtest.h>

#include <map>
#include <string>
#include <tuple>
#include <utility>

#include "ember/io/mesh_io.hpp"
#include "support/cli_harness.hpp"
#include "support/mesh_checks.hpp"
#include "support/shapes.hpp"

namespace {

using namespace ember::clitest;

/// [0,2]^3 all in material `first`, [1,3]^3 all in `second`.
std::pair<ember::Mesh, ember::Mesh> two_boxes(const std::string& first, const std::string& second) {
  ember::Mesh a = ember::test::box({0, 0, 0}, {2, 2, 2}), b = ember::test::box({1, 1, 1}, {3, 3, 3});
  a.face_groups.assign(a.face_count(), 0);
  a.group_names = {first};
  b.face_groups.assign(b.face_count(), 0);
  b.group_names = {second};
  return {a, b};
}

TEST(CliMaterials, ObjMaterialsSurviveABoolean) {
  TempDir dir;
  const auto [a, b] = two_boxes("red", "blue");
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

/// `m` with vertices at equal positions merged (glTF splits them at uv seams).
ember::Mesh welded(ember::Mesh m) {
  std::map<std::tuple<double, double, double>, std::uint32_t> at;
  std::vector<std::uint32_t> to(m.vertices.size());
  for (std::size_t v = 0; v < m.vertices.size(); ++v)
    to[v] =
        at.emplace(std::tuple{m.vertices[v].x, m.vertices[v].y, m.vertices[v].z}, static_cast<std::uint32_t>(at.size()))
            .first->second;
  for (std::uint32_t& i : m.indices) i = to[i];
  m.vertices.resize(at.size());
  for (const auto& [p, i] : at) m.vertices[i] = {std::get<0>(p), std::get<1>(p), std::get<2>(p)};
  return m;
}

/// A per-vertex "uv" that is a linear function of position: (x, y) or (y, z).
void add_uv(ember::Mesh& m, bool xy) {
  ember::MeshProperty uv{"uv", 2, false, {}};
  for (const ember::Vec3d& p : m.vertices)
    uv.values.insert(uv.values.end(), {float(xy ? p.x : p.y), float(xy ? p.y : p.z)});
  m.properties.push_back(uv);
}

TEST(CliMaterials, GlbAndObjMaterialsAndUvsSurviveAUnionIntoGltf) {
  TempDir dir;
  auto [a, b] = two_boxes("gold", "glass");
  add_uv(a, true);
  add_uv(b, false);
  write_file(dir / "a.glb", ember::write_gltf(a, true));
  ember::write_mesh(b, dir / "b.obj");
  for (const char* out : {"out.glb", "out.gltf"}) {
    const RunResult r = run_cli(dir, {"union", "a.glb", "b.obj", "-o", out});
    ASSERT_EQ(r.exit_code, 0) << describe(r);
    const ember::Mesh m = ember::read_mesh(dir / out);
    EXPECT_EQ(m.group_names, (std::vector<std::string>{"gold", "glass"})) << out;
    EXPECT_EQ(ember::test::volume(m), 15.0) << out;
    EXPECT_EQ(ember::test::unbalanced_edges(welded(m)), 0u) << out;
    // Each corner's uv is its own operand's linear field at the corner: (x, y) on gold, (y, z) on glass.
    ASSERT_EQ(m.properties.size(), 1u) << out;
    const ember::MeshProperty& uv = m.properties[0];
    for (std::size_t f = 0; f < m.face_count(); ++f)
      for (const std::uint32_t v : m.face(f)) {
        const ember::Vec3d p = m.vertices[v];
        const bool gold = m.face_groups[f] == 0;
        EXPECT_NEAR(uv.values[2 * v], gold ? p.x : p.y, 1e-6) << out;
        EXPECT_NEAR(uv.values[2 * v + 1], gold ? p.y : p.z, 1e-6) << out;
      }
  }
}

}  // namespace
