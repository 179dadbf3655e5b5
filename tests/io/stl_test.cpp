#include <gtest/gtest.h>

#include <array>
#include <bit>
#include <limits>
#include <cstring>

#include "ember/io/mesh_io.hpp"
#include "support/io_files.hpp"

namespace ember {
namespace {

// Out of line on purpose: GCC 12.2 at -O2/-O3 (SLP vectorizer) miscompiles
// {double(float(a)), double(float(b)), ...} in one expression, dropping the
// rounding of the first two lanes.
[[gnu::noinline]] double round_to_float(double d) { return static_cast<float>(d); }
Vec3d to_float(Vec3d v) { return {round_to_float(v.x), round_to_float(v.y), round_to_float(v.z)}; }

/// A binary STL with the given triangles (9 floats each), header text as given.
std::string binary_stl(const std::vector<std::array<float, 9>>& tris, std::string header = "test") {
  std::string out(84 + 50 * tris.size(), '\0');
  header.resize(80, ' ');
  std::memcpy(out.data(), header.data(), 80);
  const auto n = static_cast<std::uint32_t>(tris.size());
  std::memcpy(out.data() + 80, &n, 4);
  for (std::size_t t = 0; t < tris.size(); ++t) std::memcpy(out.data() + 84 + 50 * t + 12, tris[t].data(), 36);
  return out;
}

TEST(Stl, BinaryRoundTripEqualsFloatRoundedMeshAndWeldsVertices) {
  const Mesh sphere = test::uv_sphere(10, 16);
  const std::string bytes = write_stl(sphere);
  EXPECT_EQ(bytes.size(), 84 + 50 * sphere.triangle_count());
  const Mesh back = read_stl(bytes, "sphere.stl");
  // Welding recovers exactly the indexed mesh: same vertex count and faces.
  ASSERT_EQ(back.vertices.size(), sphere.vertices.size());
  ASSERT_EQ(back.face_count(), sphere.face_count());
  for (std::size_t f = 0; f < back.face_count(); ++f)
    for (std::size_t k = 0; k < 3; ++k)
      EXPECT_EQ(back.vertices[back.face(f)[k]], to_float(sphere.vertices[sphere.face(f)[k]]));
}

TEST(Stl, WriterFanTriangulatesPolygonsAndComputesUnitNormals) {
  const Mesh cube = test::cube_quads();
  const std::string bytes = write_stl(cube);
  std::uint32_t n;
  std::memcpy(&n, bytes.data() + 80, 4);
  EXPECT_EQ(n, 12u);
  // First quad (0,2,3,1) lies in z=0 facing -z.
  float normal[3];
  std::memcpy(normal, bytes.data() + 84, 12);
  EXPECT_EQ(normal[0], 0.0f);
  EXPECT_EQ(normal[1], 0.0f);
  EXPECT_EQ(normal[2], -1.0f);
  const Mesh back = read_stl(bytes, "cube.stl");
  EXPECT_EQ(back.vertices.size(), 8u);
  EXPECT_EQ(back.triangle_count(), 12u);
  EXPECT_FALSE(bytes.starts_with("solid"));
}

TEST(Stl, BinaryFileStartingWithSolidIsReadAsBinary) {
  const std::string bytes = binary_stl({{0, 0, 0, 1, 0, 0, 0, 1, 0}, {1, 0, 0, 1, 1, 0, 0, 1, 0}},
                                       "solid exported by a tool that writes solid in binary headers");
  const Mesh m = read_stl(bytes, "solid_header.stl");
  EXPECT_EQ(m.face_count(), 2u);
  EXPECT_EQ(m.vertices.size(), 4u);  // the shared edge is welded
}

TEST(Stl, PositiveAndNegativeZeroAreWelded) {
  const Mesh m = read_stl(binary_stl({{0, 0, 0, 1, 0, 0, 0, 1, 0}, {-0.0f, 0, -0.0f, 0, -1, 0, 1, 0, 0}}), "z.stl");
  EXPECT_EQ(m.vertices.size(), 4u);
  EXPECT_EQ(m.face(0)[0], m.face(1)[0]);
  EXPECT_FALSE(std::signbit(m.vertices[m.face(1)[0]].x));
}

TEST(Stl, AsciiWithSeveralSolidsAndUppercaseKeywords) {
  const std::string text =
      "solid first part\n"
      "  facet normal 0 0 1\n    outer loop\n      vertex 0 0 0\n      vertex 1 0 0\n      vertex 0 1 0\n"
      "    endloop\n  endfacet\n"
      "  facet normal 0 0 1\n    outer loop\n      vertex 1 0 0\n      vertex 1 1 0\n      vertex 0 1 -0\n"
      "    endloop\n  endfacet\n"
      "endsolid first part\n"
      "SOLID second\r\nFACET NORMAL 0 0 0\r\nOUTER LOOP\r\nVERTEX 5 5 5\r\nVERTEX 6 5 5\r\nVERTEX 5 6 5\r\n"
      "ENDLOOP\r\nENDFACET\r\nENDSOLID second\r\n";
  const Mesh m = read_stl(text, "ascii.stl");
  EXPECT_EQ(m.face_count(), 3u);
  EXPECT_EQ(m.vertices.size(), 7u);
  EXPECT_EQ(m.vertices[3], (Vec3d{1, 1, 0}));
}

TEST(Stl, BinaryErrorsGiveByteOffsets) {
  std::string bytes = binary_stl({{0, 0, 0, 1, 0, 0, 0, 1, 0}, {1, 0, 0, 1, 1, 0, 0, 1, 0}});
  EXPECT_ERROR_HAS(read_stl(bytes.substr(0, bytes.size() - 7), "cut.stl"), "cut.stl: byte 80:", "declares 2 triangles",
                   "184 bytes", "has only 177 bytes");
  const float nan = std::numeric_limits<float>::quiet_NaN();
  std::memcpy(bytes.data() + 84 + 50 + 12 + 12 + 4, &nan, 4);  // triangle 1, corner 1, y
  EXPECT_ERROR_HAS(read_stl(bytes, "nan.stl"), "nan.stl: byte 162:", "triangle 1 corner 1", "non-finite y coordinate");
  EXPECT_ERROR_HAS(read_stl("garbage", "tiny.stl"), "tiny.stl", "too short");
}

TEST(Stl, BinaryWithTrailingBytesIsReadWithAWarning) {
  const std::string exact = binary_stl({{0, 0, 0, 1, 0, 0, 0, 1, 0}, {1, 0, 0, 1, 1, 0, 0, 1, 0}});
  for (const std::string& tail :
       {std::string(1, '\0'), std::string(49, 'x'), std::string(50, '\0'), std::string(1000, '\xff')}) {
    std::vector<std::string> warnings;
    const Mesh m = read_stl(exact + tail, "long.stl", &warnings);
    EXPECT_EQ(m.face_count(), 2u);
    EXPECT_EQ(m.vertices.size(), 4u);
    ASSERT_EQ(warnings.size(), 1u);
    EXPECT_NE(
        warnings[0].find("long.stl: binary STL has " + std::to_string(tail.size()) + " bytes after the 2 triangles"),
        std::string::npos)
        << warnings[0];
    EXPECT_EQ(warnings[0].find("truncated"), std::string::npos) << warnings[0];
    EXPECT_EQ(read_stl(exact + tail, "long.stl").face_count(), 2u);  // no warnings list: still read
  }
  std::vector<std::string> none;
  EXPECT_EQ(read_stl(exact, "exact.stl", &none).face_count(), 2u);
  EXPECT_TRUE(none.empty());
}

TEST(Stl, AsciiWithoutEndsolidIsReadWithAWarning) {
  // Other tools accept such files; the facets are complete, so they
  // are read and the missing line is reported as a warning, not an error.
  const std::string text =
      "solid a\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\nendloop\nendfacet\n";
  std::vector<std::string> warnings;
  const Mesh m = read_stl(text, "open.stl", &warnings);
  EXPECT_EQ(m.face_count(), 1u);
  EXPECT_EQ(m.vertices.size(), 3u);
  ASSERT_EQ(warnings.size(), 1u);
  EXPECT_NE(warnings[0].find("open.stl: ASCII STL ends without 'endsolid'"), std::string::npos) << warnings[0];
  EXPECT_EQ(read_stl(text, "open.stl").face_count(), 1u);  // no warnings list: still read
  // A cut inside a facet is still an error.
  EXPECT_ERROR_HAS(read_stl("solid a\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\n", "cut.stl"), "cut.stl:");
}

TEST(Stl, AsciiErrorsGiveLines) {
  EXPECT_ERROR_HAS(read_stl("solid a\nfacet normal 0 0 1\nouter loop\nvertex 0 zero 0\n", "num.stl"),
                   "num.stl:4:", "vertex y coordinate", "'zero'");
  EXPECT_ERROR_HAS(read_stl("solid a\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nendloop\n"
                            "endfacet\nendsolid a\n",
                            "two.stl"),
                   "two.stl:6:", "2 vertices");
  EXPECT_ERROR_HAS(read_stl("solid a\nfacet normal 0 0 1\nouter loop\nvertex inf 0 0\n", "inf.stl"),
                   "inf.stl:4:", "not finite");
  EXPECT_ERROR_HAS(read_stl("solid a\nfacet normal 0 0 1\nouter lop\n", "kw.stl"), "kw.stl:3:", "expected 'loop'");
}

TEST(Stl, WriterRejectsCoordinatesBeyondFloatRange) {
  Mesh m;
  m.add_vertex({1e300, 0, 0});
  m.add_vertex({0, 1, 0});
  m.add_vertex({0, 0, 1});
  m.add_face({0, 1, 2});
  EXPECT_ERROR_HAS(write_stl(m), "STL", "float");
}

}  // namespace
}  // namespace ember

TEST(Stl, CountsTrianglesThatFloat32MakesDegenerate) {
  ember::Mesh m;
  m.vertices = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1 + 1e-12, 0, 0}, {1, 1e-12, 0}};
  m.add_face({0, 1, 2});  // fine in float
  m.add_face({1, 3, 4});  // its corners all round to (1, 0, 0) in float
  EXPECT_EQ(ember::stl_degenerate_triangles(m), 1u);
  m.add_face({0, 2, 1});
  EXPECT_EQ(ember::stl_degenerate_triangles(m), 1u);
}
