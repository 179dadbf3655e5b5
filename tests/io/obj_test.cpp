#include <gtest/gtest.h>

#include "ember/io/mesh_io.hpp"
#include "support/io_files.hpp"

namespace ember {
namespace {

using test::awkward_mesh;
using test::bit_identical;

TEST(Obj, RoundTripIsBitExact) {
  const Mesh m = awkward_mesh();
  const Mesh back = read_obj(write_obj(m), "rt.obj");
  EXPECT_TRUE(bit_identical(m, back));
  EXPECT_TRUE(std::signbit(back.vertices[0].z));  // -0.0 survives
  const Mesh sphere = test::uv_sphere(12, 17);
  EXPECT_TRUE(bit_identical(sphere, read_obj(write_obj(sphere), "s.obj")));
}

TEST(Obj, AcceptsIndexSyntaxVariantsAndNegativeIndices) {
  const std::string text =
      "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n"
      "vt 0 0\nvn 0 0 1\n"
      "f 1/1/1 2/1/1 3/1/1\n"  // v/vt/vn
      "f 1//1 3//1 4//1\n"     // v//vn
      "f 1/1 2/1 3/1 4/1\n"    // v/vt, quad
      "f -4 -3 -2\n";          // relative to the 4 vertices so far
  const Mesh m = read_obj(text, "variants.obj");
  ASSERT_EQ(m.face_count(), 4u);
  EXPECT_EQ(std::vector<std::uint32_t>(m.face(0).begin(), m.face(0).end()), (std::vector<std::uint32_t>{0, 1, 2}));
  EXPECT_EQ(std::vector<std::uint32_t>(m.face(1).begin(), m.face(1).end()), (std::vector<std::uint32_t>{0, 2, 3}));
  EXPECT_EQ(m.face_size(2), 4u);
  EXPECT_EQ(std::vector<std::uint32_t>(m.face(3).begin(), m.face(3).end()), (std::vector<std::uint32_t>{0, 1, 2}));
  EXPECT_EQ(m.triangle_count(), 5u);
}

TEST(Obj, IgnoresStatementsItDoesNotUseAndHandlesLayout) {
  const std::string text =
      "# comment line\r\n"
      "mtllib scene.mtl\r\n"
      "o thing\r\ng group1 group2\r\ns off\r\nusemtl red\r\n"
      "v\t+1.5  -2e0\t3 # trailing comment\r\n"
      "v 4 5 6 1.0\r\n"                  // homogeneous w
      "v 7 8 \\\n 9 0.5 0.25 0.125\r\n"  // continuation, then an RGB color
      "vp 0.5\r\nvn 0 0 1\r\nvt 0.1 0.2 0.3\r\n"
      "\r\n   \r\n"
      "l 1 2\r\n"
      "f 1 2 \\\r\n 3\r\n";
  const Mesh m = read_obj(text, "layout.obj");
  ASSERT_EQ(m.vertices.size(), 3u);
  EXPECT_EQ(m.vertices[0], (Vec3d{1.5, -2, 3}));
  EXPECT_EQ(m.vertices[1], (Vec3d{4, 5, 6}));
  EXPECT_EQ(m.vertices[2], (Vec3d{7, 8, 9}));
  ASSERT_EQ(m.face_count(), 1u);
  EXPECT_EQ(m.face_size(0), 3u);
}

TEST(Obj, ForwardReferencedVerticesAreAccepted) {
  const Mesh m = read_obj("f 1 2 3\nv 0 0 0\nv 1 0 0\nv 0 1 0\n", "fwd.obj");
  EXPECT_EQ(m.face_count(), 1u);
  EXPECT_EQ(m.vertices.size(), 3u);
}

TEST(Obj, IndexOutOfRangeNamesFileLineAndVertexCount) {
  const std::string text = "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n# x\nf 1 2 9001\n";
  EXPECT_ERROR_HAS(read_obj(text, "bunny.obj"), "bunny.obj:6:", "face index 9001 out of range", "file has 3 vertices");
  EXPECT_ERROR_HAS(read_obj("v 0 0 0\nv 1 0 0\nv 0 1 0\nf -1 -2 -4\n", "neg.obj"), "neg.obj:4:", "-4",
                   "3 vertices defined so far");
  EXPECT_ERROR_HAS(read_obj("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 0 1 2\n", "zero.obj"), "zero.obj:4:", "index 0");
  EXPECT_ERROR_HAS(read_obj("v 0 0 0\nf 1 1 99999999999999999999\n", "big.obj"), "big.obj:2:", "out of range");
}

TEST(Obj, DegenerateFacesAreRejected) {
  EXPECT_ERROR_HAS(read_obj("v 0 0 0\nv 1 0 0\nf 1 2\n", "two.obj"), "two.obj:3:", "2 vertices");
  EXPECT_ERROR_HAS(read_obj("v 0 0 0\nf\n", "none.obj"), "none.obj:2:", "0 vertices");
}

TEST(Obj, BadNumbersAreRejectedWithLine) {
  EXPECT_ERROR_HAS(read_obj("v 0 0 0\nv 1 abc 0\n", "a.obj"), "a.obj:2:", "vertex y coordinate", "'abc'");
  EXPECT_ERROR_HAS(read_obj("v 0 0 nan\n", "n.obj"), "n.obj:1:", "not finite");
  EXPECT_ERROR_HAS(read_obj("v inf 0 0\n", "i.obj"), "i.obj:1:", "not finite");
  EXPECT_ERROR_HAS(read_obj("v 1e999 0 0\n", "r.obj"), "r.obj:1:", "out of range");
  EXPECT_ERROR_HAS(read_obj("v 0 0\n", "short.obj"), "short.obj:1:", "expected vertex z coordinate");
  EXPECT_ERROR_HAS(read_obj("v 1.5x 0 0\n", "x.obj"), "x.obj:1:", "'1.5x'");
  EXPECT_ERROR_HAS(read_obj("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3a\n", "f.obj"), "f.obj:4:", "face index");
  EXPECT_ERROR_HAS(read_obj("v 0 0 0 1 2 3 4 5\n", "many.obj"), "many.obj:1:", "more than 7 values");
}

TEST(Obj, UnknownStatementsAndBinaryGarbageAreRejected) {
  EXPECT_ERROR_HAS(read_obj("v 0 0 0\nbogus 1 2\n", "u.obj"), "u.obj:2:", "unknown OBJ statement 'bogus'");
  const std::string garbage("\x01\x02\xff\xfe\x00 zz", 8);
  EXPECT_ERROR_HAS(read_obj(garbage, "g.obj"), "g.obj:1:", "unknown OBJ statement", "\\x01");
}

TEST(Obj, EmptyInputIsAnEmptyMesh) {
  const Mesh m = read_obj("# nothing\n", "empty.obj");
  EXPECT_TRUE(m.empty());
  EXPECT_TRUE(m.vertices.empty());
}

TEST(Obj, ExtremeFaceIndicesAreErrorsWithTheValueAndLine) {
  const std::string v = "v 0 0 0\nv 1 0 0\nv 0 1 0\n";
  // The most negative int64 must not wrap around to a valid index.
  EXPECT_ERROR_HAS(read_obj(v + "f 1 2 -9223372036854775808\n", "min.obj"), "min.obj:4:", "-9223372036854775808",
                   "out of range");
  EXPECT_ERROR_HAS(read_obj(v + "f 1 2 9223372036854775807\n", "max.obj"), "max.obj:4:", "9223372036854775807",
                   "out of range");
  EXPECT_ERROR_HAS(read_obj(v + "f 1 2 -99999999999999999999\n", "big.obj"), "big.obj:4:", "-99999999999999999999",
                   "out of range");
  EXPECT_ERROR_HAS(read_obj(v + "f 1 2 4294967297\n", "wrap.obj"), "wrap.obj:4:", "4294967297", "out of range");
  EXPECT_ERROR_HAS(read_obj(v + "f 1 2 -4\n", "neg.obj"), "neg.obj:4:", "-4", "out of range");
}

TEST(Obj, UsemtlGivesNamedFaceGroupsThatWriteBack) {
  const std::string v = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\n";
  // Faces before the first usemtl form an unnamed group after the named ones.
  const Mesh m = read_obj(v + "f 1 3 2\nusemtl red\nf 1 2 4\nusemtl blue\nf 2 3 4\nusemtl red\nf 1 4 3\n", "g.obj");
  EXPECT_EQ(m.face_groups, (std::vector<std::uint32_t>{2, 0, 1, 0}));
  EXPECT_EQ(m.group_names, (std::vector<std::string>{"red", "blue", ""}));
  const std::string text = write_obj(m);
  EXPECT_NE(text.find("usemtl group_2\nf 1 3 2\nusemtl red\n"), std::string::npos) << text;
  const Mesh back = read_obj(text, "back.obj");
  EXPECT_EQ(back.face_groups, (std::vector<std::uint32_t>{0, 1, 2, 1}));
  EXPECT_EQ(back.group_names, (std::vector<std::string>{"group_2", "red", "blue"}));
  // Without usemtl there are no groups.
  EXPECT_TRUE(read_obj(v + "f 1 3 2\n", "plain.obj").face_groups.empty());
  EXPECT_ERROR_HAS(read_obj(v + "usemtl\nf 1 2 3\n", "m.obj"), "m.obj:5:", "usemtl without a material name");
  Mesh bad = m;
  bad.group_names[0] = "two words";
  EXPECT_ERROR_HAS(write_obj(bad), "group name 'two words'");
}

TEST(Obj, TextureAndNormalIndicesGivePerCornerPropertiesThatWriteBack) {
  const std::string text =
      "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nvt 0 0\nvt 1 0\nvt 0.5 1\nvn 0 0 -1\n"
      "f 1/1/1 3/3/1 2/2/1\nf 1/1 2/2 4/3\nf 2//1 3//1 4//1\nf 1 4 3\n";
  const Mesh m = read_obj(text, "t.obj");
  ASSERT_EQ(m.properties.size(), 2u);
  const MeshProperty& uv = m.properties[0];
  EXPECT_EQ(uv.name, "uv");
  EXPECT_TRUE(uv.per_corner);
  EXPECT_EQ(uv.values,
            (std::vector<float>{0, 0, 0.5, 1, 1, 0, 0, 0, 1, 0, 0.5, 1, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0}));
  EXPECT_EQ(m.properties[1].name, "normal");
  EXPECT_EQ(m.properties[1].values.size(), 36u);
  EXPECT_EQ(m.properties[1].values[2], -1.0f);
  // Written back as one vt/vn per corner; the same properties read again.
  EXPECT_EQ(read_obj(write_obj(m), "back.obj").properties, m.properties);
  EXPECT_TRUE(read_obj("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n", "plain.obj").properties.empty());
  // A reference past the vt lines drops the texture coordinates, with a warning.
  std::vector<std::string> warnings;
  const Mesh dropped = read_obj("v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nf 1/1 2/2 3/1\n", "r.obj", &warnings);
  EXPECT_TRUE(dropped.properties.empty());
  EXPECT_EQ(dropped.face_count(), 1u);
  ASSERT_EQ(warnings.size(), 1u);
  EXPECT_EQ(warnings[0], "r.obj: texture index 2 out of range (file has 1); texture coordinates dropped");
  EXPECT_ERROR_HAS(read_obj("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1/x 2 3\n", "x.obj"), "x.obj:4:", "malformed face corner");
}

}  // namespace
}  // namespace ember
