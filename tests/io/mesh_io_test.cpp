#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sys/stat.h>
#include <unistd.h>

#include <thread>

#include "ember/io/mesh_io.hpp"
#include "support/io_files.hpp"

namespace ember {
namespace {

namespace fs = std::filesystem;

/// A fresh directory under the system temp dir, removed afterwards.
class TempDir {
 public:
  TempDir() : path_(fs::temp_directory_path() / ("ember_io_test_" + std::to_string(::getpid()))) {
    fs::remove_all(path_);
    fs::create_directories(path_);
  }
  ~TempDir() { fs::remove_all(path_); }
  const fs::path& path() const { return path_; }

 private:
  fs::path path_;
};

TEST(MeshIo, FormatFromExtensionIsCaseInsensitive) {
  EXPECT_EQ(format_from_path("a/b/bunny.OBJ"), MeshFormat::Obj);
  EXPECT_EQ(format_from_path("x.Stl"), MeshFormat::Stl);
  EXPECT_EQ(format_from_path("x.off"), MeshFormat::Off);
  EXPECT_EQ(format_from_path("x.PLY"), MeshFormat::Ply);
  EXPECT_ERROR_HAS(format_from_path("model.3ds"), "model.3ds", "'.3ds'", ".obj, .stl, .off, .ply");
  EXPECT_ERROR_HAS(format_from_path("noext"), "noext", "supported");
}

TEST(MeshIo, FileRoundTripForEveryFormat) {
  TempDir dir;
  const Mesh m = test::awkward_mesh();
  for (const char* name : {"m.obj", "m.off", "m.ply"}) {
    const fs::path p = dir.path() / name;
    write_mesh(m, p);
    EXPECT_TRUE(test::bit_identical(m, read_mesh(p))) << name;
  }
  // STL keeps floats only, and welds by position: compare with the float cube.
  const Mesh cube = test::cube_quads();
  write_mesh(cube, dir.path() / "c.STL");
  const Mesh back = read_mesh(dir.path() / "c.STL");
  EXPECT_EQ(back.vertices.size(), 8u);
  EXPECT_EQ(back.triangle_count(), 12u);
}

TEST(MeshIo, EmptyMeshRoundTrips) {
  const Mesh empty;
  for (MeshFormat f : {MeshFormat::Obj, MeshFormat::Off, MeshFormat::Ply, MeshFormat::Stl}) {
    const Mesh back = read_mesh(write_mesh(empty, f), f, "empty");
    EXPECT_TRUE(back.empty());
    EXPECT_TRUE(back.vertices.empty());
  }
}

TEST(MeshIo, MissingFileAndDirectoryAreNamed) {
  TempDir dir;
  EXPECT_ERROR_HAS(read_mesh(dir.path() / "nope.obj"), "nope.obj", "cannot open");
  fs::create_directories(dir.path() / "d.stl");
  EXPECT_ERROR_HAS(read_mesh(dir.path() / "d.stl"), "d.stl", "directory");
}

TEST(MeshIo, DevicesAreRefusedButFifosAreRead) {
  TempDir dir;
  fs::create_symlink("/dev/zero", dir.path() / "zero.stl");
  EXPECT_ERROR_HAS(read_mesh(dir.path() / "zero.stl"), "zero.stl", "character device", "not a mesh file");
  EXPECT_ERROR_HAS(read_meshes(dir.path() / "zero.stl"), "zero.stl", "character device");
  const fs::path fifo = dir.path() / "pipe.obj";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  std::thread writer([&] { std::ofstream(fifo) << "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n"; });
  const Mesh m = read_mesh(fifo);
  writer.join();
  EXPECT_EQ(m.face_count(), 1u);
}

TEST(MeshIo, WriteFailureThrows) {
  TempDir dir;
  EXPECT_ERROR_HAS(write_mesh(test::cube_quads(), dir.path() / "missing_dir" / "x.obj"), "x.obj", "cannot open");
  EXPECT_ERROR_HAS(write_mesh(test::cube_quads(), dir.path() / "x.xyz"), "x.xyz", "unknown mesh file extension");
  if (fs::exists("/dev/full")) {
    // A device that is always full: the failure shows on write or close.
    EXPECT_THROW(write_mesh(test::uv_sphere(60, 60), fs::path("/dev/full") / ".." / "full"), Error);
  }
}

TEST(MeshIo, WritersRejectMalformedMeshes) {
  Mesh m = test::cube_quads();
  m.indices[5] = 99;
  for (MeshFormat f : {MeshFormat::Obj, MeshFormat::Off, MeshFormat::Ply, MeshFormat::Stl})
    EXPECT_ERROR_HAS(write_mesh(m, f), "index 99", "8 vertices");
  Mesh two;
  two.add_vertex({0, 0, 0});
  two.add_vertex({1, 0, 0});
  two.add_face({0, 1});
  EXPECT_ERROR_HAS(write_obj(two), "fewer than 3");
}

TEST(MeshIo, WritersRejectNonFiniteCoordinates) {
  const auto dir = fs::temp_directory_path() / ("ember_nonfinite_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  for (const double bad : {std::nan(""), HUGE_VAL, -HUGE_VAL}) {
    Mesh m = test::cube_quads();
    m.vertices[3].y = bad;
    for (MeshFormat f : {MeshFormat::Obj, MeshFormat::Off, MeshFormat::Ply, MeshFormat::Stl, MeshFormat::ThreeMf}) {
      EXPECT_ERROR_HAS(write_mesh(m, f), "vertex 3", "non-finite");
      try {
        (void)write_mesh(m, f);
      } catch (const Error& e) {
        EXPECT_EQ(e.where().vertex, std::optional<std::size_t>(3));
      }
    }
    for (const char* name : {"m.obj", "m.off", "m.ply", "m.stl", "m.3mf"}) {
      EXPECT_ERROR_HAS(write_mesh(m, dir / name), (dir / name).string(), "vertex 3", "non-finite");
      EXPECT_FALSE(fs::exists(dir / name)) << name;
    }
  }
  Mesh out_of_range = test::cube_quads();
  out_of_range.indices[0] = 8;
  EXPECT_ERROR_HAS(write_mesh(out_of_range, dir / "r.obj"), "r.obj", "index 8", "out of range");
  EXPECT_FALSE(fs::exists(dir / "r.obj"));
  fs::remove_all(dir);
}

TEST(MeshIo, ReadMeshDispatchesOnExtension) {
  TempDir dir;
  // An ASCII STL body under a .stl name must go through the STL reader.
  const fs::path p = dir.path() / "tri.stl";
  std::ofstream(p) << "solid t\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\n"
                      "endloop\nendfacet\nendsolid t\n";
  const Mesh m = read_mesh(p);
  EXPECT_EQ(m.face_count(), 1u);
  EXPECT_EQ(m.vertices.size(), 3u);
  // Errors from the readers carry the path given.
  std::ofstream(dir.path() / "bad.off") << "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 7\n";
  EXPECT_ERROR_HAS(read_mesh(dir.path() / "bad.off"), (dir.path() / "bad.off").string() + ":6:", "face index 7");
}

}  // namespace
}  // namespace ember
