// glTF 2.0 (tinygltf): round trips with materials, node transforms, strips
// and fans, and malformed files refused with the file's name.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <string>
#include <vector>

#include "ember/io/mesh_io.hpp"
#include "support/io_files.hpp"
#include "support/mesh_checks.hpp"
#include "support/shapes.hpp"

namespace ember {
namespace {

std::string base64(const std::string& in) {
  static const char* k = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  std::size_t i = 0;
  for (; i + 2 < in.size(); i += 3) {
    const unsigned v = (unsigned char)in[i] << 16 | (unsigned char)in[i + 1] << 8 | (unsigned char)in[i + 2];
    out += {k[v >> 18], k[(v >> 12) & 63], k[(v >> 6) & 63], k[v & 63]};
  }
  if (i + 1 == in.size()) {
    const unsigned v = (unsigned char)in[i] << 16;
    out += {k[v >> 18], k[(v >> 12) & 63], '=', '='};
  } else if (i + 2 == in.size()) {
    const unsigned v = (unsigned char)in[i] << 16 | (unsigned char)in[i + 1] << 8;
    out += {k[v >> 18], k[(v >> 12) & 63], k[(v >> 6) & 63], '='};
  }
  return out;
}

/// A glTF file of the unit tetrahedron's 4 positions and 12 indices in one
/// buffer; `extra` goes into the top-level object, `node` is the one node.
std::string tetra_gltf(const std::string& node = R"({"mesh": 0})", const std::string& primitive_extra = "",
                       std::size_t index_count = 12, int mode = 4) {
  const float p[12] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1};
  const std::uint32_t idx[12] = {0, 2, 1, 0, 1, 3, 1, 2, 3, 0, 3, 2};
  std::string bytes(reinterpret_cast<const char*>(p), 48);
  bytes.append(reinterpret_cast<const char*>(idx), 48);
  return R"({"asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0]}], "nodes": [)" + node +
         R"(], "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "indices": 1, "mode": )" +
         std::to_string(mode) + primitive_extra + R"(}]}],
  "buffers": [{"byteLength": 96, "uri": "data:application/octet-stream;base64,)" +
         base64(bytes) + R"("}],
  "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 48}, {"buffer": 0, "byteOffset": 48, "byteLength": 48}],
  "accessors": [{"bufferView": 0, "componentType": 5126, "count": 4, "type": "VEC3", "min": [0,0,0], "max": [1,1,1]},
                {"bufferView": 1, "componentType": 5125, "count": )" +
         std::to_string(index_count) + R"(, "type": "SCALAR"}]})";
}

TEST(Gltf, RoundTripsKeepPositionsFacesAndMaterials) {
  Mesh m = test::box({0, 0, 0}, {2, 2, 2});
  m.face_groups.assign(m.face_count(), 0);
  for (std::size_t f = 6; f < m.face_count(); ++f) m.face_groups[f] = 3;
  m.group_names = {"red", "", "", ""};
  for (const bool binary : {false, true}) {
    const std::string bytes = write_gltf(m, binary);
    EXPECT_EQ(bytes, write_gltf(m, binary)) << "output must be deterministic";
    const Mesh back = read_gltf(bytes, "rt", binary);
    EXPECT_EQ(back.vertices, m.vertices);
    EXPECT_EQ(back.face_count(), m.face_count());
    EXPECT_EQ(back.group_names, (std::vector<std::string>{"red", "group_3"}));
    EXPECT_EQ(test::volume(back), 8.0);
    std::size_t red = 0;
    for (const std::uint32_t g : back.face_groups) red += g == 0;
    EXPECT_EQ(red, 6u);
  }
  // Without groups: one primitive, no material, no groups read back.
  const Mesh plain = read_gltf(write_gltf(test::box({0, 0, 0}, {1, 1, 1}), true), "p", true);
  EXPECT_TRUE(plain.face_groups.empty());
  EXPECT_EQ(plain.face_count(), 12u);
}

TEST(Gltf, NodeTransformsAreAppliedAndMirrorsKeepTheOutside) {
  const Mesh moved = read_gltf(tetra_gltf(R"({"mesh": 0, "translation": [10, 0, 0], "scale": [2, 2, 2]})"), "t", false);
  EXPECT_EQ(moved.vertices[1], (Vec3d{12, 0, 0}));
  EXPECT_DOUBLE_EQ(test::volume(moved), 8.0 / 6.0);
  // A mirror (negative determinant) flips the winding back outward.
  const Mesh mirrored = read_gltf(tetra_gltf(R"({"mesh": 0, "scale": [-1, 1, 1]})"), "m", false);
  EXPECT_DOUBLE_EQ(test::volume(mirrored), 1.0 / 6.0);
  const Mesh matrix =
      read_gltf(tetra_gltf(R"({"mesh": 0, "matrix": [1,0,0,0, 0,1,0,0, 0,0,1,0, 0,0,5,1]})"), "mat", false);
  EXPECT_EQ(matrix.vertices[3], (Vec3d{0, 0, 6}));
}

TEST(Gltf, StripsAndFansBecomeTriangles) {
  EXPECT_EQ(read_gltf(tetra_gltf(R"({"mesh": 0})", "", 6, 5), "strip", false).face_count(), 4u);
  EXPECT_EQ(read_gltf(tetra_gltf(R"({"mesh": 0})", "", 6, 6), "fan", false).face_count(), 4u);
  // Points bound no volume: skipped.
  EXPECT_EQ(read_gltf(tetra_gltf(R"({"mesh": 0})", "", 12, 0), "points", false).face_count(), 0u);
}

TEST(Gltf, MalformedFilesAreRefusedWithTheirName) {
  EXPECT_ERROR_HAS(read_gltf("{not json", "bad.gltf", false), "bad.gltf", "not a valid glTF file");
  EXPECT_ERROR_HAS(read_gltf("glTF\x02\0\0\0", "bad.glb", true), "bad.glb", "not a valid GLB file");
  // 13 indices in a 48-byte view: past the buffer.
  EXPECT_ERROR_HAS(read_gltf(tetra_gltf(R"({"mesh": 0})", "", 13), "long.gltf", false), "long.gltf",
                   "reaches past its buffer");
  EXPECT_ERROR_HAS(read_gltf(tetra_gltf(R"({"mesh": 7})"), "m.gltf", false), "m.gltf", "mesh 7 does not exist");
  EXPECT_ERROR_HAS(read_gltf(tetra_gltf(R"({"mesh": 0, "children": [0]})"), "cycle.gltf", false), "cycle.gltf",
                   "deeper than 256 levels");
  EXPECT_ERROR_HAS(read_gltf(tetra_gltf(R"({"mesh": 0})", R"(, "material": 0)"), "mat.gltf", false), "mat.gltf",
                   "material 0 does not exist");
  const std::string external = R"({"asset": {"version": "2.0"}, "buffers": [{"byteLength": 4, "uri": "side.bin"}]})";
  EXPECT_ERROR_HAS(read_gltf(external, "ext.gltf", false), "ext.gltf");
}

TEST(Gltf, UvsAndNormalsRoundTripWithSeamsSplitIntoVertices) {
  Mesh m = test::box({0, 0, 0}, {1, 1, 1});
  MeshProperty uv{"uv", 2, true, {}}, normal{"normal", 3, true, {}};
  for (std::size_t f = 0; f < m.face_count(); ++f)
    for (std::size_t k = 0; k < 3; ++k) {
      uv.values.insert(uv.values.end(), {float(f) / 12.0f, float(k) / 3.0f});  // a seam at every edge
      normal.values.insert(normal.values.end(), {0.0f, 0.0f, 1.0f});
    }
  m.properties = {uv, normal};
  for (const bool binary : {false, true}) {
    const Mesh back = read_gltf(write_gltf(m, binary), "uv", binary);
    ASSERT_EQ(back.face_count(), m.face_count());
    ASSERT_EQ(back.properties.size(), 2u);
    const MeshProperty& buv = back.properties[0];
    EXPECT_EQ(buv.name, "uv");
    EXPECT_FALSE(buv.per_corner);  // glTF attributes are per vertex
    for (std::size_t c = 0; c < back.indices.size(); ++c) {
      EXPECT_EQ(buv.values[2 * back.indices[c]], uv.values[2 * c]);
      EXPECT_EQ(buv.values[2 * back.indices[c] + 1], uv.values[2 * c + 1]);
      EXPECT_EQ(back.vertices[back.indices[c]], m.vertices[m.indices[c]]);
    }
    EXPECT_EQ(back.properties[1].name, "normal");
  }
}

TEST(Gltf, NormalsFollowTheNodeTransformsInverseTranspose) {
  // A node scaling x by 2 turns the normal (1, 1, 0)/sqrt 2 into (1/2, 1, 0) normalized.
  Mesh m = test::box({0, 0, 0}, {1, 1, 1});
  m.properties = {{"normal", 3, false, std::vector<float>(3 * m.vertices.size(), 0.0f)}};
  for (std::size_t v = 0; v < m.vertices.size(); ++v) {
    m.properties[0].values[3 * v] = float(1 / std::sqrt(2.0));
    m.properties[0].values[3 * v + 1] = float(1 / std::sqrt(2.0));
  }
  std::string text = write_gltf(m, false);
  const std::string node = "\"mesh\": 0";
  text.replace(text.find(node), node.size(), "\"mesh\": 0, \"scale\": [2, 1, 1]");
  const Mesh back = read_gltf(text, "scaled", false);
  const std::vector<float>& n = back.properties[0].values;
  EXPECT_NEAR(n[0], 0.5 / std::sqrt(1.25), 1e-6);
  EXPECT_NEAR(n[1], 1.0 / std::sqrt(1.25), 1e-6);
  for (std::size_t c = 0; c < back.indices.size(); ++c)
    EXPECT_EQ(back.vertices[back.indices[c]].x, 2.0 * m.vertices[m.indices[c]].x);
}

}  // namespace
}  // namespace ember
