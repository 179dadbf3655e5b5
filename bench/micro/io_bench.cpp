// Mesh I/O throughput: parse speed of in-memory files (no disk I/O in the
// timed loop) for a ~1M-triangle sphere in every format, plus a real large
// STL from the shared data when it is present. Reported as bytes/s.
#include <benchmark/benchmark.h>

#include "ember/shapes.hpp"

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "ember/io/mesh_io.hpp"

namespace {

/// UV sphere with 2*segments*(rings-1) triangles.
const ember::Mesh& big_sphere() {
  static const ember::Mesh m = ember::shapes::uv_sphere({0, 0, 0}, 1.0, 708, 708);  // ~1.0M triangles
  return m;
}

const std::string& serialized(ember::MeshFormat f) {
  static std::string cache[4];
  std::string& s = cache[static_cast<int>(f)];
  if (s.empty()) s = ember::write_mesh(big_sphere(), f);
  return s;
}

void read_format(benchmark::State& state, ember::MeshFormat f) {
  const std::string& bytes = serialized(f);
  for (auto _ : state) {
    ember::Mesh m = ember::read_mesh(bytes, f, "bench");
    benchmark::DoNotOptimize(m.indices.data());
  }
  state.SetBytesProcessed(static_cast<std::int64_t>(state.iterations() * bytes.size()));
  state.counters["MB"] = static_cast<double>(bytes.size()) / 1e6;
  state.counters["triangles"] = static_cast<double>(big_sphere().triangle_count());
}

void BM_ReadObj(benchmark::State& s) { read_format(s, ember::MeshFormat::Obj); }
void BM_ReadStlBinary(benchmark::State& s) { read_format(s, ember::MeshFormat::Stl); }
void BM_ReadOff(benchmark::State& s) { read_format(s, ember::MeshFormat::Off); }
void BM_ReadPlyBinary(benchmark::State& s) { read_format(s, ember::MeshFormat::Ply); }
BENCHMARK(BM_ReadObj)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_ReadStlBinary)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_ReadOff)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_ReadPlyBinary)->Unit(benchmark::kMillisecond);

void BM_ReadStlAscii(benchmark::State& state) {
  // ASCII STL of the same sphere, written here since the library writes binary.
  static const std::string bytes = [] {
    const ember::Mesh& m = big_sphere();
    std::string out = "solid sphere\n";
    char buf[160];
    for (std::size_t f = 0; f < m.face_count(); ++f) {
      out += "facet normal 0 0 0\nouter loop\n";
      for (auto i : m.face(f)) {
        const auto& v = m.vertices[i];
        std::snprintf(buf, sizeof buf, "vertex %.9g %.9g %.9g\n", v.x, v.y, v.z);
        out += buf;
      }
      out += "endloop\nendfacet\n";
    }
    return out + "endsolid sphere\n";
  }();
  for (auto _ : state) {
    ember::Mesh m = ember::read_stl(bytes, "bench");
    benchmark::DoNotOptimize(m.indices.data());
  }
  state.SetBytesProcessed(static_cast<std::int64_t>(state.iterations() * bytes.size()));
  state.counters["MB"] = static_cast<double>(bytes.size()) / 1e6;
}
BENCHMARK(BM_ReadStlAscii)->Unit(benchmark::kMillisecond);

void BM_WriteObj(benchmark::State& state) {
  std::size_t bytes = 0;
  for (auto _ : state) {
    std::string s = ember::write_obj(big_sphere());
    bytes = s.size();
    benchmark::DoNotOptimize(s.data());
  }
  state.SetBytesProcessed(static_cast<std::int64_t>(state.iterations() * bytes));
}
BENCHMARK(BM_WriteObj)->Unit(benchmark::kMillisecond);

/// A real file: the largest STL in shared/data/large, parsed from memory.
void BM_ReadSharedLargeStl(benchmark::State& state) {
  const std::filesystem::path path =
      std::filesystem::path(EMBER_SHARED_DATA_DIR) / "large" / "thingi10k_32770_midpoint2.stl";
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    state.SkipWithError(("shared data file not found: " + path.string()).c_str());
    return;
  }
  std::stringstream ss;
  ss << in.rdbuf();
  const std::string bytes = ss.str();
  std::size_t triangles = 0;
  for (auto _ : state) {
    ember::Mesh m = ember::read_stl(bytes, path.string());
    triangles = m.triangle_count();
    benchmark::DoNotOptimize(m.indices.data());
  }
  state.SetBytesProcessed(static_cast<std::int64_t>(state.iterations() * bytes.size()));
  state.counters["triangles"] = static_cast<double>(triangles);
}
BENCHMARK(BM_ReadSharedLargeStl)->Unit(benchmark::kMillisecond);

/// The same file through read_mesh, including the disk read (page cache warm).
void BM_ReadMeshFromDisk(benchmark::State& state) {
  const std::filesystem::path path =
      std::filesystem::path(EMBER_SHARED_DATA_DIR) / "large" / "thingi10k_32770_midpoint2.stl";
  if (!std::filesystem::exists(path)) {
    state.SkipWithError(("shared data file not found: " + path.string()).c_str());
    return;
  }
  for (auto _ : state) {
    ember::Mesh m = ember::read_mesh(path);
    benchmark::DoNotOptimize(m.indices.data());
  }
  state.SetBytesProcessed(static_cast<std::int64_t>(state.iterations() * std::filesystem::file_size(path)));
}
BENCHMARK(BM_ReadMeshFromDisk)->Unit(benchmark::kMillisecond);

}  // namespace
