#include <gtest/gtest.h>

#include "ember/io/mesh_io.hpp"
#include "support/io_files.hpp"

namespace ember {
namespace {

TEST(Off, RoundTripIsBitExact) {
  const Mesh m = test::awkward_mesh();
  EXPECT_TRUE(test::bit_identical(m, read_off(write_off(m), "rt.off")));
  const Mesh cube = test::cube_quads();
  EXPECT_TRUE(test::bit_identical(cube, read_off(write_off(cube), "cube.off")));
}

TEST(Off, ColorAndNormalHeadersWithCommentsAndFaceColors) {
  const std::string coff =
      "COFF\n# a comment\n\n4 2 0 # counts\n"
      "0 0 0 255 0 0 255\n1 0 0 0 255 0 255\n1 1 0 0 0 255 255\n0 1 0 9 9 9 255\n"
      "3 0 1 2 255 0 0\n"           // face with RGB color
      "3 0 2 3 0.5 0.5 0.5 1.0\n";  // face with RGBA color
  const Mesh m = read_off(coff, "c.off");
  EXPECT_EQ(m.vertices.size(), 4u);
  EXPECT_EQ(m.vertices[2], (Vec3d{1, 1, 0}));
  EXPECT_EQ(m.face_count(), 2u);
  EXPECT_EQ(m.face(1)[2], 3u);
  for (const char* header : {"NOFF", "CNOFF", "STOFF", "STCNOFF"}) {
    const Mesh n = read_off(std::string(header) + "\n3 1\n0 0 0 0 0 1\n1 0 0 0 0 1\n0 1 0 0 0 1\n3 0 1 2\n", header);
    EXPECT_EQ(n.face_count(), 1u) << header;
  }
}

TEST(Off, HeaderLayoutVariants) {
  // Counts on the header line, glued to the keyword, and without edge count.
  const std::string body = "0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n";
  EXPECT_EQ(read_off("OFF 3 1 0\n" + body, "a.off").face_count(), 1u);
  EXPECT_EQ(read_off("\t  OFF3 1 0 # glued\n" + body, "b.off").face_count(), 1u);
  EXPECT_EQ(read_off("OFF\n3 1\n" + body, "c.off").face_count(), 1u);
  EXPECT_EQ(read_off("\xEF\xBB\xBFOFF\r\n3 1 0\r\n0 0 0\r\n1 0 0\r\n0 1 0\r\n3 0 1 2\r\n", "bom.off").face_count(), 1u);
}

TEST(Off, CountsThatDisagreeWithContentAreErrors) {
  EXPECT_ERROR_HAS(read_off("OFF\n4 1 0\n0 0 0\n1 0 0\n0 1 0\n", "v.off"), "v.off:6:", "after 3 of the 4 vertices");
  EXPECT_ERROR_HAS(read_off("OFF\n3 2 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n", "f.off"),
                   "f.off:7:", "after 1 of the 2 faces");
  EXPECT_ERROR_HAS(read_off("OFF\n3 1 0\n0 0 0\n1 0\n0 1 0\n3 0 1 2\n", "short.off"),
                   "short.off:4:", "vertex z coordinate", "end of line");
  EXPECT_ERROR_HAS(read_off("OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n4 0 1 2\n# pad\n", "fs.off"), "fs.off:6:", "face index",
                   "end of line");
  EXPECT_ERROR_HAS(read_off("OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n9 0 1 2\n", "fc.off"), "fc.off:6:", "9 vertices");
  EXPECT_ERROR_HAS(read_off("OFF\n99999999999 1 0\n", "huge.off"), "huge.off:2:", "99999999999 vertices");
  EXPECT_ERROR_HAS(read_off("OFF\n-3 1 0\n", "neg.off"), "neg.off:2:", "negative");
}

TEST(Off, BadIndicesFacesAndValues) {
  const std::string head = "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n";
  EXPECT_ERROR_HAS(read_off(head + "3 0 1 3\n", "r.off"), "r.off:6:", "face index 3 out of range", "3 vertices");
  EXPECT_ERROR_HAS(read_off(head + "3 0 -1 2\n", "n.off"), "n.off:6:", "face index -1");
  EXPECT_ERROR_HAS(read_off(head + "2 0 1\n", "d.off"), "d.off:6:", "2 vertices");
  EXPECT_ERROR_HAS(read_off("OFF\n3 1 0\n0 0 0\n1 nan 0\n0 1 0\n3 0 1 2\n", "nan.off"), "nan.off:4:", "not finite");
  EXPECT_ERROR_HAS(read_off("OFX\n", "h.off"), "h.off:1:", "OFF header");
  EXPECT_ERROR_HAS(read_off("4OFF\n", "4d.off"), "4d.off:1:", "only 3D");
  EXPECT_ERROR_HAS(read_off("OFF BINARY\n", "bin.off"), "bin.off:1:", "binary OFF");
  EXPECT_ERROR_HAS(read_off("", "empty.off"), "empty.off:1:", "empty file");
}

}  // namespace
}  // namespace ember
