#include <gtest/gtest.h>

#include <bit>
#include <cstring>
#include <limits>

#include "ember/error.hpp"
#include "ember/io/mesh_io.hpp"
#include "support/io_files.hpp"

namespace ember {
namespace {

/// Appends v in the given byte order (to build binary PLY bodies by hand).
template <class T>
void put(std::string& out, T v, bool big) {
  char buf[sizeof(T)];
  std::memcpy(buf, &v, sizeof(T));
  if (big != (std::endian::native == std::endian::big))
    for (std::size_t i = 0; i < sizeof(T) / 2; ++i) std::swap(buf[i], buf[sizeof(T) - 1 - i]);
  out.append(buf, sizeof(T));
}

const char* kMixedHeader =
    "element material 1\n"  // an element the reader must skip, before the vertices
    "property list uchar char name\n"
    "element vertex 4\n"
    "property float x\nproperty double confidence\nproperty float32 y\nproperty float z\n"
    "property list ushort float64 weights\n"
    "element face 2\n"
    "property int16 flags\n"
    "property list uint8 uint16 vertex_index\n"
    "property list int ushort texnumber\n"
    "element edge 1\nproperty int vertex1\nproperty uint vertex2\n"
    "end_header\n";

/// The same mixed-type file in either byte order.
std::string mixed_binary(bool big) {
  std::string out = std::string("ply\nformat ") + (big ? "binary_big_endian" : "binary_little_endian") +
                    " 1.0\ncomment mixed types\nobj_info test\n" + kMixedHeader;
  put<std::uint8_t>(out, 3, big);
  out += "abc";
  const float xyz[4][3] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0.5f}};
  for (int v = 0; v < 4; ++v) {
    put<float>(out, xyz[v][0], big);
    put<double>(out, 0.25 * v, big);
    put<float>(out, xyz[v][1], big);
    put<float>(out, xyz[v][2], big);
    put<std::uint16_t>(out, static_cast<std::uint16_t>(v), big);
    for (int k = 0; k < v; ++k) put<double>(out, k, big);
  }
  const std::uint16_t faces[2][4] = {{0, 1, 2, 0}, {0, 2, 3, 1}};
  for (int f = 0; f < 2; ++f) {
    put<std::int16_t>(out, -1, big);
    const std::uint8_t n = f == 0 ? 3 : 4;
    put<std::uint8_t>(out, n, big);
    for (int k = 0; k < n; ++k) put<std::uint16_t>(out, faces[f][k], big);
    put<std::int32_t>(out, 1, big);
    put<std::uint16_t>(out, 7, big);
  }
  put<std::int32_t>(out, 0, big);
  put<std::uint32_t>(out, 1, big);
  return out;
}

void expect_mixed_mesh(const Mesh& m) {
  ASSERT_EQ(m.vertices.size(), 4u);
  EXPECT_EQ(m.vertices[3], (Vec3d{0, 1, 0.5}));
  ASSERT_EQ(m.face_count(), 2u);
  EXPECT_EQ(m.face_size(1), 4u);
  EXPECT_EQ(m.face(1)[3], 1u);
  EXPECT_EQ(m.triangle_count(), 3u);
}

TEST(Ply, BinaryLittleRoundTripIsBitExact) {
  const Mesh m = test::awkward_mesh();
  const std::string bytes = write_ply(m);
  EXPECT_NE(bytes.find("format binary_little_endian 1.0"), std::string::npos);
  EXPECT_TRUE(test::bit_identical(m, read_ply(bytes, "rt.ply")));
}

TEST(Ply, ProvenanceIsWrittenAsFaceProperties) {
  const Mesh m = test::awkward_mesh();
  std::vector<Provenance> prov;
  for (std::uint32_t f = 0; f < m.face_count(); ++f) prov.push_back({f % 3, 1000000 + 7 * f});
  const std::string bytes = write_ply(m, prov);
  EXPECT_NE(bytes.find("int vertex_indices\nproperty uint operand\nproperty uint source_face\nend_header\n"),
            std::string::npos);
  // The properties are skipped by the reader: the mesh reads back bit-exact.
  EXPECT_TRUE(test::bit_identical(m, read_ply(bytes, "prov.ply")));
  // Decode the face records by hand: uchar count, int indices, uint operand, uint source_face.
  std::size_t at = bytes.find("end_header\n") + 11 + m.vertices.size() * 24;
  auto take = [&](auto v) {
    std::memcpy(&v, bytes.data() + at, sizeof v);
    at += sizeof v;
    return v;
  };
  for (std::size_t f = 0; f < m.face_count(); ++f) {
    ASSERT_EQ(take(std::uint8_t{}), m.face_size(f));
    for (const std::uint32_t i : m.face(f)) EXPECT_EQ(take(std::int32_t{}), static_cast<std::int32_t>(i));
    EXPECT_EQ(take(std::uint32_t{}), prov[f].operand);
    EXPECT_EQ(take(std::uint32_t{}), prov[f].face);
  }
  EXPECT_EQ(at, bytes.size());
  // Without provenance the file is the plain one.
  EXPECT_EQ(write_ply(m, {}), write_ply(m));
  EXPECT_EQ(write_ply(m).find("operand"), std::string::npos);
}

TEST(Ply, ProvenanceOfTheWrongLengthIsAnError) {
  const Mesh m = test::awkward_mesh();
  const std::vector<Provenance> one{{0, 0}};
  ASSERT_GT(m.face_count(), 1u);
  try {
    (void)write_ply(m, one);
    FAIL() << "expected an error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("1 provenance entries for " + std::to_string(m.face_count()) + " faces"),
              std::string::npos)
        << e.what();
  }
}

TEST(Ply, WriterWidensListCountForLargeFaces) {
  Mesh m;
  std::vector<std::uint32_t> big;
  for (std::uint32_t i = 0; i < 300; ++i) {
    m.add_vertex({std::cos(i * 0.01), std::sin(i * 0.01), 0});
    big.push_back(i);
  }
  m.add_face(big);
  const std::string bytes = write_ply(m);
  EXPECT_NE(bytes.find("property list uint int vertex_indices"), std::string::npos);
  EXPECT_TRUE(test::bit_identical(m, read_ply(bytes, "big.ply")));
}

TEST(Ply, BinaryBothByteOrdersWithMixedTypesListsAndExtraElements) {
  expect_mixed_mesh(read_ply(mixed_binary(false), "le.ply"));
  expect_mixed_mesh(read_ply(mixed_binary(true), "be.ply"));
}

TEST(Ply, AsciiWithExtraPropertiesAndElements) {
  const std::string text = std::string("ply\r\nformat ascii 1.0\r\ncomment hi\r\n") + kMixedHeader +
                           "3 97 98 99\n"
                           "0 0 0 0 0\n1 0.25 0 0 1 0\n1 0.5 1 0 2 0 1\n0 0.75 1 0.5 3 0 1 2\n"
                           "-1 3 0 1 2 1 7\n-1 4 0 2 3 1 0\n"
                           "0 1\n";
  expect_mixed_mesh(read_ply(text, "mixed.ply"));
}

TEST(Ply, ErrorsInHeaders) {
  EXPECT_ERROR_HAS(read_ply("plx\n", "a.ply"), "a.ply:1:", "not a PLY file");
  EXPECT_ERROR_HAS(read_ply("ply\nformat binary_middle_endian 1.0\nend_header\n", "b.ply"),
                   "b.ply:2:", "unknown PLY format");
  EXPECT_ERROR_HAS(read_ply("ply\nformat ascii 1.0\nelement vertex 1\nproperty flot x\nend_header\n", "c.ply"),
                   "c.ply:4:", "'flot'");
  EXPECT_ERROR_HAS(read_ply("ply\nformat ascii 1.0\nelement vertex 0\n", "d.ply"), "d.ply", "no 'end_header'");
  EXPECT_ERROR_HAS(read_ply("ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\n"
                            "end_header\n0 0\n",
                            "e.ply"),
                   "e.ply", "no 'z' property");
  EXPECT_ERROR_HAS(
      read_ply("ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\n"
               "property float z\nelement face 1\nproperty list uchar int corners\nend_header\n0 0 0\n3 0 0 0\n",
               "f.ply"),
      "f.ply", "no 'vertex_indices'");
  EXPECT_ERROR_HAS(read_ply("ply\nformat ascii 1.0\nelement tristrips 1\nproperty list int int vertex_indices\n"
                            "end_header\n3 0 1 2\n",
                            "t.ply"),
                   "t.ply", "tristrips");
}

const std::string kAsciiHead =
    "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
    "element face 1\nproperty list uchar int vertex_indices\nend_header\n";

TEST(Ply, AsciiCountsAndValuesMustMatchContent) {
  EXPECT_ERROR_HAS(read_ply(kAsciiHead + "0 0 0\n1 0 0\n0 1 0\n3 0 1 3\n", "r.ply"),
                   "r.ply:13:", "face index 3 out of range", "3 vertices");
  EXPECT_ERROR_HAS(read_ply(kAsciiHead + "0 0 0\n1 0 0\n0 1 0\n", "trunc.ply"), "trunc.ply:", "face vertex count");
  EXPECT_ERROR_HAS(read_ply(kAsciiHead + "0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n3 0 1 2\n", "extra.ply"),
                   "extra.ply:14:", "unexpected");
  EXPECT_ERROR_HAS(read_ply(kAsciiHead + "0 0 0\n1 0 0 7\n0 1 0\n3 0 1 2\n", "wide.ply"),
                   "wide.ply:11:", "extra value");
  EXPECT_ERROR_HAS(read_ply(kAsciiHead + "0 0 0\n1 nan 0\n0 1 0\n3 0 1 2\n", "nan.ply"), "nan.ply:11:", "not finite");
  EXPECT_ERROR_HAS(read_ply(kAsciiHead + "0 0 0\n1 0 0\n0 1 0\n2 0 1\n", "deg.ply"), "deg.ply:13:", "2 vertices");
}

TEST(Ply, BinaryErrorsGiveByteOffsets) {
  const Mesh cube = test::cube_quads();
  const std::string bytes = write_ply(cube);
  const std::size_t body = bytes.find("end_header\n") + 11;
  EXPECT_ERROR_HAS(read_ply(bytes.substr(0, bytes.size() - 2), "cut.ply"), "cut.ply: byte", "file ends inside");
  std::string bad = bytes;
  const double nan = std::numeric_limits<double>::quiet_NaN();
  std::memcpy(bad.data() + body + 24 * 2 + 8, &nan, 8);  // vertex 2, y
  EXPECT_ERROR_HAS(read_ply(bad, "nan.ply"), "nan.ply: byte " + std::to_string(body + 56), "not finite");
  bad = bytes;
  const std::int32_t idx = 8;
  const std::size_t first_index = body + 8 * 24 + 1;
  std::memcpy(bad.data() + first_index, &idx, 4);
  EXPECT_ERROR_HAS(read_ply(bad, "idx.ply"), "idx.ply: byte " + std::to_string(first_index),
                   "face index 8 out of range", "8 vertices");
  EXPECT_ERROR_HAS(read_ply(bytes + "xx", "tail.ply"), "tail.ply: byte " + std::to_string(bytes.size()),
                   "unexpected 2 bytes");
}

TEST(Ply, HugeDeclaredCountsFailBeforeAllocating) {
  const std::string text =
      "ply\nformat binary_little_endian 1.0\nelement vertex 400000000\nproperty double x\nproperty double y\n"
      "property double z\nend_header\n";
  EXPECT_ERROR_HAS(read_ply(text, "huge.ply"), "huge.ply", "400000000");
}

}  // namespace
}  // namespace ember
