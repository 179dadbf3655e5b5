// Readers accept a UTF-8 byte-order mark before the header (some
// Windows tools write one), and an empty OBJ file is an error.
#include <gtest/gtest.h>

#include "ember/io/mesh_io.hpp"
#include "support/io_files.hpp"

namespace ember {
namespace {

const std::string kBom = "\xEF\xBB\xBF";

TEST(ByteOrderMark, AcceptedBeforeEveryTextHeader) {
  const Mesh cube = test::cube_quads();
  for (const MeshFormat f : {MeshFormat::Obj, MeshFormat::Off, MeshFormat::Ply}) {
    SCOPED_TRACE(static_cast<int>(f));
    const Mesh back = read_mesh(kBom + write_mesh(cube, f), f, "bom");
    EXPECT_TRUE(test::bit_identical(cube, back));
  }
  // ASCII PLY and ASCII STL too (the writers above produce binary PLY).
  const std::string ply =
      "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
      "property float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n"
      "0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n";
  EXPECT_EQ(read_ply(kBom + ply, "a.ply").face_count(), 1u);
  const std::string stl =
      "solid a\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\n"
      "endloop\nendfacet\nendsolid a\n";
  EXPECT_EQ(read_stl(kBom + stl, "a.stl").face_count(), 1u);
  // Only at the very start: elsewhere it is still malformed input.
  EXPECT_ERROR_HAS(read_obj("v 0 0 0\n" + kBom + "v 1 0 0\n", "mid.obj"), "mid.obj:2:");
}

TEST(EmptyObj, ZeroBytesOrOnlyBlanksIsNoFacesError) {
  EXPECT_ERROR_HAS(read_obj("", "e.obj"), "e.obj", "no faces in e.obj");
  EXPECT_ERROR_HAS(read_obj(" \n\r\n", "b.obj"), "no faces in b.obj");
  EXPECT_ERROR_HAS(read_obj(kBom, "bom.obj"), "no faces in bom.obj");
  // A comment-only file (what ember writes for an empty result) stays valid.
  EXPECT_EQ(read_obj("# written by ember\n", "c.obj").face_count(), 0u);
}

}  // namespace
}  // namespace ember
