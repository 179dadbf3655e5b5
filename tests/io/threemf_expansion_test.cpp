// 3MF component bombs: objects that each hold copies of the previous one
// expand exponentially; the reader sizes the expansion before lib3mf
// resolves it and refuses beyond the ReadOptions limits.
#include <gtest/gtest.h>
#include <zlib.h>

#include <chrono>
#include <string>

#include "ember/io/mesh_io.hpp"
#include "io/threemf_scan.hpp"
#include "support/io_files.hpp"

namespace ember {
namespace {

void put16(std::string& s, std::uint32_t v) {
  s += static_cast<char>(v & 0xff);
  s += static_cast<char>((v >> 8) & 0xff);
}
void put32(std::string& s, std::uint32_t v) {
  put16(s, v & 0xffff);
  put16(s, v >> 16);
}

/// A ZIP archive of stored (uncompressed) entries.
std::string zip_stored(const std::vector<std::pair<std::string, std::string>>& entries) {
  std::string out, directory;
  for (const auto& [name, data] : entries) {
    const auto crc = static_cast<std::uint32_t>(
        crc32(0, reinterpret_cast<const Bytef*>(data.data()), static_cast<uInt>(data.size())));
    const auto offset = static_cast<std::uint32_t>(out.size());
    put32(out, 0x04034b50);
    put16(out, 20), put16(out, 0), put16(out, 0), put16(out, 0), put16(out, 0);
    put32(out, crc), put32(out, static_cast<std::uint32_t>(data.size())),
        put32(out, static_cast<std::uint32_t>(data.size()));
    put16(out, static_cast<std::uint32_t>(name.size())), put16(out, 0);
    out += name;
    out += data;
    put32(directory, 0x02014b50);
    put16(directory, 20), put16(directory, 20), put16(directory, 0), put16(directory, 0), put16(directory, 0),
        put16(directory, 0);
    put32(directory, crc), put32(directory, static_cast<std::uint32_t>(data.size())),
        put32(directory, static_cast<std::uint32_t>(data.size()));
    put16(directory, static_cast<std::uint32_t>(name.size())), put16(directory, 0), put16(directory, 0);
    put16(directory, 0), put16(directory, 0), put32(directory, 0), put32(directory, offset);
    directory += name;
  }
  const auto dir_offset = static_cast<std::uint32_t>(out.size());
  out += directory;
  put32(out, 0x06054b50);
  put16(out, 0), put16(out, 0), put16(out, static_cast<std::uint32_t>(entries.size())),
      put16(out, static_cast<std::uint32_t>(entries.size()));
  put32(out, static_cast<std::uint32_t>(directory.size())), put32(out, dir_offset), put16(out, 0);
  return out;
}

/// A 3MF file: a tetrahedron (object 1) and `depth` objects, each with two
/// translated copies of the one before; the build item is the last, which
/// expands to 2^depth tetrahedra.
std::string nested_3mf(int depth) {
  std::string model =
      "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<model unit=\"millimeter\" xml:lang=\"en-US\" "
      "xmlns=\"http://schemas.microsoft.com/3dmanufacturing/core/2015/02\"><resources>"
      "<object id=\"1\" type=\"model\"><mesh><vertices><vertex x=\"0\" y=\"0\" z=\"0\"/><vertex x=\"1\" y=\"0\" "
      "z=\"0\"/><vertex x=\"0\" y=\"1\" z=\"0\"/><vertex x=\"0\" y=\"0\" z=\"1\"/></vertices><triangles>"
      "<triangle v1=\"0\" v2=\"2\" v3=\"1\"/><triangle v1=\"0\" v2=\"1\" v3=\"3\"/><triangle v1=\"0\" v2=\"3\" "
      "v3=\"2\"/><triangle v1=\"1\" v2=\"2\" v3=\"3\"/></triangles></mesh></object>";
  for (int d = 1; d <= depth; ++d) {
    const std::string prev = std::to_string(d), id = std::to_string(d + 1);
    model += "<object id=\"" + id + "\" type=\"model\"><components><component objectid=\"" + prev +
             "\"/><component objectid=\"" + prev + "\" transform=\"1 0 0 0 1 0 0 0 1 " + std::to_string(2 * d) +
             " 0 0\"/></components></object>";
  }
  model += "</resources><build><item objectid=\"" + std::to_string(depth + 1) + "\"/></build></model>\n";
  const std::string types =
      "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<Types "
      "xmlns=\"http://schemas.openxmlformats.org/package/2006/content-types\"><Default Extension=\"rels\" "
      "ContentType=\"application/vnd.openxmlformats-package.relationships+xml\"/><Default Extension=\"model\" "
      "ContentType=\"application/vnd.ms-package.3dmanufacturing-3dmodel+xml\"/></Types>";
  const std::string rels =
      "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<Relationships "
      "xmlns=\"http://schemas.openxmlformats.org/package/2006/relationships\"><Relationship "
      "Target=\"/3D/3dmodel.model\" "
      "Id=\"rel0\" Type=\"http://schemas.microsoft.com/3dmanufacturing/2013/01/3dmodel\"/></Relationships>";
  return zip_stored({{"[Content_Types].xml", types}, {"_rels/.rels", rels}, {"3D/3dmodel.model", model}});
}

TEST(ThreeMfExpansion, ScanReadsDeflatedAndStoredPackages) {
  // lib3mf's writer deflates the model part.
  const auto deflated = io_detail::scan_3mf_expansion(write_3mf(test::cube_quads()));
  ASSERT_TRUE(deflated.has_value());
  EXPECT_EQ(deflated->stored_triangles, 12u);
  EXPECT_EQ(deflated->expanded_triangles, 12u);
  const auto stored = io_detail::scan_3mf_expansion(nested_3mf(5));
  ASSERT_TRUE(stored.has_value());
  EXPECT_EQ(stored->stored_triangles, 4u);
  EXPECT_EQ(stored->expanded_triangles, 4u << 5);
  EXPECT_EQ(stored->instances, (2u << 5) - 1);
  EXPECT_FALSE(io_detail::scan_3mf_expansion("not a zip").has_value());
}

TEST(ThreeMfExpansion, ShallowNestingIsReadWithEveryCopy) {
  const std::vector<Mesh> meshes = read_3mf(nested_3mf(3), "nested3.3mf");
  ASSERT_EQ(meshes.size(), 1u);
  EXPECT_EQ(meshes[0].face_count(), 8u * 4u);
  EXPECT_EQ(meshes[0].vertices.size(), 8u * 4u);
}

TEST(ThreeMfExpansion, ComponentBombsAreRefusedBeforeExpanding) {
  for (const int depth : {20, 40, 70}) {
    SCOPED_TRACE(depth);
    const std::string bytes = nested_3mf(depth);
    EXPECT_LT(bytes.size(), 16000u);  // uncompressed; a deflated one is smaller still
    const auto start = std::chrono::steady_clock::now();
    EXPECT_ERROR_HAS(read_3mf(bytes, "bomb.3mf"), "bomb.3mf: 3MF: the build items expand to", "triangles",
                     "max_3mf_triangles", "--max-3mf-triangles");
    EXPECT_LT(std::chrono::steady_clock::now() - start, std::chrono::seconds(5));
  }
  // 2^70 tetrahedra: the count saturates rather than wrapping to a small number.
  EXPECT_ERROR_HAS(read_3mf(nested_3mf(70), "bomb.3mf"), "expand to 18446744073709551615 triangles");
}

TEST(ThreeMfExpansion, LimitsCanBeRaisedAndLowered) {
  // 2^12 tetrahedra = 16384 triangles: within the defaults.
  const std::string bytes = nested_3mf(12);
  EXPECT_EQ(read_3mf(bytes, "n.3mf").front().face_count(), 16384u);
  ReadOptions tight;
  tight.max_3mf_triangles = 10000;
  EXPECT_ERROR_HAS(read_3mf(bytes, "n.3mf", tight), "n.3mf", "16384 triangles", "more than the limit of 10000");
  // 2^18 tetrahedra (1 million triangles from 4 stored): refused by the
  // instancing ratio, read once it is raised.
  const std::string deep = nested_3mf(18);
  EXPECT_ERROR_HAS(read_3mf(deep, "d.3mf"), "d.3mf", "1048576 triangles", "times what it stores");
  ReadOptions trusting;
  trusting.max_3mf_instancing = std::uint64_t{1} << 40;
  EXPECT_EQ(read_3mf(deep, "d.3mf", trusting).front().face_count(), std::size_t{1} << 20);
}

}  // namespace
}  // namespace ember
