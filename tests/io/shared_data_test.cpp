// Reads the shared corpus (../shared/data): every file in MANIFEST.tsv must
// load with the triangle count the manifest lists, and every dirty/peer test
// file must either load or fail with ember::Error.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

#include "ember/error.hpp"
#include "ember/io/mesh_io.hpp"

namespace fs = std::filesystem;

namespace {

const fs::path kDataDir = EMBER_SHARED_DATA_DIR;

std::vector<std::string> split_tabs(const std::string& line) {
  std::vector<std::string> cols;
  std::stringstream ss(line);
  std::string col;
  while (std::getline(ss, col, '\t')) cols.push_back(col);
  return cols;
}

bool is_mesh_extension(const fs::path& p) {
  std::string ext = p.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
  return ext == ".obj" || ext == ".stl" || ext == ".off" || ext == ".ply";
}

}  // namespace

TEST(SharedData, ManifestMeshesLoadWithListedTriangleCounts) {
  if (!fs::is_directory(kDataDir)) GTEST_SKIP() << "../shared/data not found: " << kDataDir;
  std::ifstream manifest(kDataDir / "MANIFEST.tsv");
  ASSERT_TRUE(manifest) << "cannot open MANIFEST.tsv in " << kDataDir;
  std::string line;
  std::getline(manifest, line);
  const auto header = split_tabs(line);
  const auto column = [&](const std::string& name) {
    const auto it = std::find(header.begin(), header.end(), name);
    return it == header.end() ? -1 : static_cast<int>(it - header.begin());
  };
  const int path_col = 0, tri_col = column("triangles");
  ASSERT_GE(tri_col, 0) << "MANIFEST.tsv has no 'triangles' column";

  std::vector<std::string> problems;
  int checked = 0;
  while (std::getline(manifest, line)) {
    if (line.empty()) continue;
    const auto cols = split_tabs(line);
    ASSERT_GT(static_cast<int>(cols.size()), tri_col) << "short manifest line: " << line;
    const fs::path file = kDataDir / cols[path_col];
    // Counts were taken after fan-triangulating polygons, matching triangle_count().
    const std::size_t expected = std::stoull(cols[tri_col]);
    try {
      const ember::Mesh mesh = ember::read_mesh(file);
      if (mesh.triangle_count() != expected)
        problems.push_back(cols[path_col] + ": " + std::to_string(mesh.triangle_count()) +
                           " triangles, manifest says " + std::to_string(expected));
    } catch (const ember::Error& e) {
      problems.push_back(cols[path_col] + ": " + e.what());
    }
    ++checked;
  }
  EXPECT_GT(checked, 0);
  std::string report;
  for (const auto& p : problems) report += "  " + p + "\n";
  EXPECT_TRUE(problems.empty()) << problems.size() << " of " << checked << " manifest files failed:\n" << report;
}

TEST(SharedData, DirtyAndPeerFilesLoadOrThrowEmberError) {
  if (!fs::is_directory(kDataDir)) GTEST_SKIP() << "../shared/data not found: " << kDataDir;
  std::vector<fs::path> files;
  for (const auto& e : fs::directory_iterator(kDataDir / "thingi10k" / "dirty"))
    if (e.is_regular_file()) files.push_back(e.path());
  for (const auto& e : fs::recursive_directory_iterator(kDataDir / "peer-tests"))
    if (e.is_regular_file() && is_mesh_extension(e.path())) files.push_back(e.path());
  std::sort(files.begin(), files.end());
  ASSERT_FALSE(files.empty());
  int loaded = 0, rejected = 0;
  for (const fs::path& f : files) {
    try {
      const ember::Mesh mesh = ember::read_mesh(f);
      // A mesh that loads must be internally consistent.
      for (std::uint32_t i : mesh.indices) ASSERT_LT(i, mesh.vertices.size()) << f;
      ASSERT_EQ(mesh.face_offsets.back(), mesh.indices.size()) << f;
      ++loaded;
    } catch (const ember::Error& e) {
      ++rejected;
      EXPECT_NE(std::string(e.what()).find(f.string()), std::string::npos)
          << "message does not name the file: " << e.what();
    }
  }
  EXPECT_EQ(loaded + rejected, static_cast<int>(files.size()));
  // Visible in the test log so a change in how many files load is noticed.
  RecordProperty("loaded", loaded);
  RecordProperty("rejected", rejected);
  std::cout << "[ shared  ] " << loaded << " loaded, " << rejected << " rejected with ember::Error\n";
}
