// 3MF through lib3mf: round trips, several objects, errors.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <unistd.h>

#include "ember/boolean.hpp"
#include "ember/io/mesh_io.hpp"
#include "support/io_files.hpp"

namespace ember {
namespace {

std::string file_bytes(const std::filesystem::path& p) {
  std::ifstream f(p, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(f), std::istreambuf_iterator<char>());
}

/// Faces fan-triangulated, as 3MF stores them.
Mesh triangulated(const Mesh& m) {
  Mesh out;
  out.vertices = m.vertices;
  for (std::size_t f = 0; f < m.face_count(); ++f) {
    const auto face = m.face(f);
    for (std::size_t i = 1; i + 1 < face.size(); ++i) out.add_face({face[0], face[i], face[i + 1]});
  }
  return out;
}

/// `back` is `m` as 3MF keeps it: the same vertices and triangles, with
/// coordinates rounded to the 6 decimals lib3mf 1.x writes.
::testing::AssertionResult same_up_to_3mf_rounding(const Mesh& back, const Mesh& m) {
  const Mesh want = triangulated(m);
  if (back.indices != want.indices || back.face_offsets != want.face_offsets)
    return ::testing::AssertionFailure() << "faces differ";
  if (back.vertices.size() != want.vertices.size()) return ::testing::AssertionFailure() << "vertex counts differ";
  for (std::size_t i = 0; i < want.vertices.size(); ++i) {
    const Vec3d a = back.vertices[i], b = want.vertices[i];
    const double d = std::max({std::abs(a.x - b.x), std::abs(a.y - b.y), std::abs(a.z - b.z)});
    if (d > 1e-6) return ::testing::AssertionFailure() << "vertex " << i << " moved by " << d;
  }
  return ::testing::AssertionSuccess();
}

TEST(ThreeMf, ExtensionIsRecognized) {
  EXPECT_EQ(format_from_path("print.3MF"), MeshFormat::ThreeMf);
  EXPECT_ERROR_HAS(format_from_path("a.xyz"), ".3mf");
}

TEST(ThreeMf, RoundTripKeepsFloatCoordinatesAndTriangles) {
  const Mesh cube = test::cube_quads();  // quads: written as two triangles each
  const Mesh back = read_mesh(write_3mf(cube), MeshFormat::ThreeMf, "cube.3mf");
  EXPECT_TRUE(same_up_to_3mf_rounding(back, cube));
  const Mesh torus = shapes::torus(1.0, 0.3, 24, 12);
  EXPECT_TRUE(
      same_up_to_3mf_rounding(read_mesh(write_mesh(torus, MeshFormat::ThreeMf), MeshFormat::ThreeMf, "t"), torus));
}

TEST(ThreeMf, SeveralObjectsAreSeparateMeshes) {
  const std::vector<Mesh> meshes{test::cube_quads(), shapes::uv_sphere({2, 0, 0}, 0.5, 8, 6)};
  const std::string bytes = write_3mf(meshes);
  const std::vector<Mesh> back = read_3mf(bytes, "two.3mf");
  ASSERT_EQ(back.size(), 2u);
  EXPECT_TRUE(same_up_to_3mf_rounding(back[0], meshes[0]));
  EXPECT_TRUE(same_up_to_3mf_rounding(back[1], meshes[1]));
  // read_mesh promises one mesh: several objects are an error that says what to do.
  EXPECT_ERROR_HAS(read_mesh(bytes, MeshFormat::ThreeMf, "two.3mf"), "two.3mf", "2 objects", "read_meshes");
}

TEST(ThreeMf, FileFunctionsFollowTheExtension) {
  const auto dir = std::filesystem::temp_directory_path() / ("ember_3mf_test_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  const Mesh torus = shapes::torus(1.0, 0.35, 32, 16);
  write_mesh(torus, dir / "torus.3mf");
  EXPECT_TRUE(same_up_to_3mf_rounding(read_mesh(dir / "torus.3mf"), torus));
  ASSERT_EQ(read_meshes(dir / "torus.3mf").size(), 1u);
  EXPECT_TRUE(same_up_to_3mf_rounding(read_meshes(dir / "torus.3mf").front(), torus));
  // Other formats: read_meshes gives the one mesh.
  write_mesh(torus, dir / "torus.obj");
  ASSERT_EQ(read_meshes(dir / "torus.obj").size(), 1u);
  // A 3MF read back is closed (rounding keeps the shared vertices) and usable.
  const Mesh sphere = shapes::uv_sphere({0.9, 0, 0.2}, 0.6, 24, 12);
  const BooleanResult r = boolean({read_mesh(dir / "torus.3mf"), sphere}, Operation::Union);
  EXPECT_GT(r.mesh.face_count(), 0u);
  EXPECT_TRUE(r.warnings.empty());
  std::filesystem::remove_all(dir);
}

TEST(ThreeMf, OutputIsTheSameBytesForTheSameMeshes) {
  const Mesh torus = shapes::torus(1.0, 0.35, 32, 16);
  const std::string first = write_3mf(torus);
  EXPECT_EQ(write_3mf(torus), first);
  const std::vector<Mesh> two{test::cube_quads(), torus};
  EXPECT_EQ(write_3mf(two), write_3mf(two));
  // Different content, different UUIDs; every UUID of a file is distinct.
  const std::string other = write_3mf(test::cube_quads());
  EXPECT_NE(other, first);
  EXPECT_TRUE(same_up_to_3mf_rounding(read_mesh(first, MeshFormat::ThreeMf, "t.3mf"), torus));
  const auto dir = std::filesystem::temp_directory_path() / ("ember_3mf_det_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  write_mesh(torus, dir / "a.3mf");
  write_mesh(torus, dir / "b.3mf");
  EXPECT_EQ(file_bytes(dir / "a.3mf"), file_bytes(dir / "b.3mf"));
  std::filesystem::remove_all(dir);
}

TEST(ThreeMf, EmptyMeshRoundTrips) {
  const std::vector<Mesh> back = read_3mf(write_3mf(Mesh{}), "empty.3mf");
  ASSERT_EQ(back.size(), 1u);
  EXPECT_TRUE(back[0].empty());
}

TEST(ThreeMf, BadInputSaysWhat) {
  EXPECT_ERROR_HAS(read_3mf("not a zip file at all", "junk.3mf"), "junk.3mf", "not a readable 3MF file");
  EXPECT_ERROR_HAS(read_3mf("", "empty.3mf"), "empty.3mf", "3MF");
  Mesh bad = test::cube_quads();
  bad.indices[3] = 99;
  EXPECT_ERROR_HAS(write_3mf(bad), "3MF", "index 99");
  Mesh far = test::cube_quads();
  far.vertices[0].x = 1e300;
  EXPECT_ERROR_HAS(write_3mf(far), "single precision");
}

}  // namespace
}  // namespace ember
