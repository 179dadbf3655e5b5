// Mutates valid files of every format at random (fixed seeds) and checks that
// the readers either return a well-formed mesh or throw ember::Error: no
// crash, no other exception type, no out-of-range index in a returned mesh.
#include <gtest/gtest.h>

#include <random>

#include "ember/io/mesh_io.hpp"
#include "support/io_files.hpp"

namespace ember {
namespace {

struct Sample {
  MeshFormat format;
  std::string bytes;
  const char* label;
};

std::vector<Sample> samples() {
  const Mesh cube = test::cube_quads();
  const Mesh sphere = test::uv_sphere(5, 7);
  std::string ascii_stl = "solid s\n";
  for (std::size_t f = 0; f < sphere.face_count(); ++f) {
    ascii_stl += "facet normal 0 0 0\nouter loop\n";
    for (auto i : sphere.face(f)) {
      const Vec3d& v = sphere.vertices[i];
      ascii_stl += "vertex " + std::to_string(v.x) + " " + std::to_string(v.y) + " " + std::to_string(v.z) + "\n";
    }
    ascii_stl += "endloop\nendfacet\n";
  }
  ascii_stl += "endsolid s\n";
  std::string ascii_ply =
      "ply\nformat ascii 1.0\nelement vertex 8\nproperty float x\nproperty float y\nproperty float z\n"
      "property uchar red\nelement face 6\nproperty list uchar int vertex_indices\nend_header\n";
  for (const Vec3d& v : cube.vertices)
    ascii_ply += std::to_string(v.x) + " " + std::to_string(v.y) + " " + std::to_string(v.z) + " 200\n";
  for (std::size_t f = 0; f < cube.face_count(); ++f) {
    ascii_ply += "4";
    for (auto i : cube.face(f)) ascii_ply.append(" ").append(std::to_string(i));
    ascii_ply += "\n";
  }
  std::string coff = write_off(cube);
  coff.replace(0, 4, "COFF\n# c\n");
  return {{MeshFormat::Obj, "v 0 0 0 # c\nvt 1 1\n" + write_obj(cube) + "f -1/1 -2/1 -3/1\n", "obj"},
          {MeshFormat::Stl, write_stl(sphere), "binary stl"},
          {MeshFormat::Stl, ascii_stl, "ascii stl"},
          {MeshFormat::Off, coff, "off"},
          {MeshFormat::Ply, write_ply(sphere), "binary ply"},
          {MeshFormat::Ply, ascii_ply, "ascii ply"}};
}

std::string mutate(std::string s, std::mt19937& rng) {
  auto pick = [&](std::size_t n) { return std::uniform_int_distribution<std::size_t>(0, n)(rng); };
  static const char kBytes[] = {'0', '9', '-', '.', ' ', '\n', '/', 'e', '#', '\\', '\0', '\xff', 'n', '\r'};
  const int edits = 1 + static_cast<int>(pick(3));
  for (int e = 0; e < edits && !s.empty(); ++e) {
    switch (pick(4)) {
      case 0: s[pick(s.size() - 1)] = static_cast<char>(pick(255)); break;          // random byte
      case 1: s[pick(s.size() - 1)] = kBytes[pick(sizeof kBytes - 1)]; break;       // syntax byte
      case 2: s.resize(pick(s.size())); break;                                      // truncate
      case 3: s.insert(pick(s.size()), 1, kBytes[pick(sizeof kBytes - 1)]); break;  // insert
      default: s.erase(pick(s.size() - 1), 1 + pick(8)); break;                     // delete run
    }
  }
  return s;
}

TEST(Fuzz, MutatedFilesLoadWellFormedOrThrowEmberError) {
  std::mt19937 rng(20240611);
  for (const Sample& sample : samples()) {
    // The unmutated sample must load, or the loop below would test nothing.
    ASSERT_NO_THROW(read_mesh(sample.bytes, sample.format, sample.label)) << sample.label;
    int loaded = 0, rejected = 0;
    for (int iter = 0; iter < 6000; ++iter) {
      const std::string bytes = mutate(sample.bytes, rng);
      try {
        const Mesh m = read_mesh(bytes, sample.format, "fuzz");
        test::expect_well_formed(m);
        ++loaded;
      } catch (const Error& e) {
        EXPECT_EQ(std::string(e.what()).rfind("fuzz", 0), 0u) << e.what();
        ++rejected;
      } catch (const std::exception& e) {
        FAIL() << sample.label << " iteration " << iter << ": non-ember exception " << e.what();
      }
    }
    // Both outcomes must occur: mutations that only touch ignored bytes load,
    // and most others are caught.
    EXPECT_GT(rejected, 0) << sample.label;
    EXPECT_GT(loaded + rejected, 5999) << sample.label;
  }
}

TEST(Fuzz, RandomBytesAreRejectedByEveryReader) {
  std::mt19937 rng(7);
  for (int iter = 0; iter < 500; ++iter) {
    std::string bytes(std::uniform_int_distribution<int>(0, 400)(rng), '\0');
    for (char& c : bytes) c = static_cast<char>(rng());
    for (MeshFormat f : {MeshFormat::Obj, MeshFormat::Stl, MeshFormat::Off, MeshFormat::Ply}) {
      try {
        const Mesh m = read_mesh(bytes, f, "random");
        test::expect_well_formed(m);
        // Random bytes may be an empty mesh only if they are blank for OBJ.
        EXPECT_TRUE(m.empty()) << "random bytes produced faces";
      } catch (const Error&) {
      }
    }
  }
}

}  // namespace
}  // namespace ember
