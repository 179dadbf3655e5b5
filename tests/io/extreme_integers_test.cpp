// Integers at and beyond the int64 limits in every reader's counts and
// indices: an error that quotes the value and says where, never a wrap-around.
#include <gtest/gtest.h>

#include "ember/io/mesh_io.hpp"
#include "support/io_files.hpp"

namespace ember {
namespace {

constexpr const char* kMin = "-9223372036854775808";
constexpr const char* kMax = "9223372036854775807";
constexpr const char* kBeyond = "99999999999999999999";

TEST(ExtremeIntegers, OffCountsAndIndices) {
  for (const char* n : {kMin, kMax, kBeyond}) {
    const std::string counts = std::string("OFF\n") + n + " 1 0\n0 0 0\n";
    EXPECT_ERROR_HAS(read_off(counts, "c.off"), "c.off:2:");
    const std::string index = std::string("OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 ") + n + "\n";
    EXPECT_ERROR_HAS(read_off(index, "i.off"), "i.off:6:", n);
    const std::string corners = std::string("OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n") + n + " 0 1 2\n";
    EXPECT_ERROR_HAS(read_off(corners, "n.off"), "n.off:6:", n);
  }
}

TEST(ExtremeIntegers, AsciiPlyCountsAndIndices) {
  const std::string head = "ply\nformat ascii 1.0\nelement vertex ";
  const std::string props =
      "\nproperty float x\nproperty float y\nproperty float z\nelement face 1\n"
      "property list uchar int vertex_indices\nend_header\n";
  for (const char* n : {kMin, kMax, kBeyond}) {
    EXPECT_ERROR_HAS(read_ply(head + n + props, "c.ply"), "c.ply:3:");
    const std::string index = head + "3" + props + "0 0 0\n1 0 0\n0 1 0\n3 0 1 " + n + "\n";
    EXPECT_ERROR_HAS(read_ply(index, "i.ply"), "i.ply:13:", n);
    const std::string corners = head + "3" + props + "0 0 0\n1 0 0\n0 1 0\n" + n + " 0 1 2\n";
    EXPECT_ERROR_HAS(read_ply(corners, "n.ply"), "n.ply:13:");
  }
}

TEST(ExtremeIntegers, BinaryStlCountBeyondTheFile) {
  std::string bytes(84, '\0');
  for (int k = 80; k < 84; ++k) bytes[k] = '\xff';
  EXPECT_ERROR_HAS(read_stl(bytes, "c.stl"), "c.stl", "4294967295 triangles");
}

}  // namespace
}  // namespace ember
