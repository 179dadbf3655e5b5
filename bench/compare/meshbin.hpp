#pragma once
// The small binary triangle-mesh format the comparison benchmark uses to hand
// one prepared operand to every runner (ember_bench, cgal_runner and
// bench/peers/manifold_runner.mjs read the same file, untimed).
//
// Layout (little endian, no padding):
//   char[4]  magic "EMB1"
//   uint64   vertex count V
//   uint64   triangle count T
//   double   positions[3V]   (x y z per vertex; every value is a float32 value)
//   uint32   triangles[3T]   (counter-clockwise seen from outside)
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <stdexcept>
#include <string>
#include <sys/resource.h>
#include <vector>

namespace bench {

struct TriMesh {
  std::vector<double> xyz;         // 3 per vertex
  std::vector<std::uint32_t> tri;  // 3 per triangle
  std::size_t vertex_count() const { return xyz.size() / 3; }
  std::size_t triangle_count() const { return tri.size() / 3; }
};

inline void write_bin(const TriMesh& m, const std::string& path) {
  std::FILE* f = std::fopen(path.c_str(), "wb");
  if (!f) throw std::runtime_error("cannot write " + path);
  const std::uint64_t v = m.vertex_count(), t = m.triangle_count();
  bool ok = std::fwrite("EMB1", 1, 4, f) == 4 && std::fwrite(&v, 8, 1, f) == 1 && std::fwrite(&t, 8, 1, f) == 1 &&
            std::fwrite(m.xyz.data(), sizeof(double), m.xyz.size(), f) == m.xyz.size() &&
            std::fwrite(m.tri.data(), sizeof(std::uint32_t), m.tri.size(), f) == m.tri.size();
  ok = (std::fclose(f) == 0) && ok;
  if (!ok) throw std::runtime_error("short write to " + path);
}

inline TriMesh read_bin(const std::string& path) {
  std::FILE* f = std::fopen(path.c_str(), "rb");
  if (!f) throw std::runtime_error("cannot open " + path);
  char magic[4];
  std::uint64_t v = 0, t = 0;
  TriMesh m;
  bool ok = std::fread(magic, 1, 4, f) == 4 && std::string(magic, 4) == "EMB1" && std::fread(&v, 8, 1, f) == 1 &&
            std::fread(&t, 8, 1, f) == 1;
  if (ok) {
    m.xyz.resize(3 * v);
    m.tri.resize(3 * t);
    ok = std::fread(m.xyz.data(), sizeof(double), m.xyz.size(), f) == m.xyz.size() &&
         std::fread(m.tri.data(), sizeof(std::uint32_t), m.tri.size(), f) == m.tri.size();
  }
  std::fclose(f);
  if (!ok) throw std::runtime_error("malformed mesh file " + path);
  for (std::uint32_t i : m.tri)
    if (i >= v) throw std::runtime_error("index out of range in " + path);
  return m;
}

/// Signed volume of a triangle soup (positive for outward-oriented closed meshes).
inline double signed_volume(const std::vector<double>& xyz, const std::vector<std::uint32_t>& tri) {
  long double vol = 0;
  for (std::size_t t = 0; t + 2 < tri.size(); t += 3) {
    const double* a = &xyz[3 * tri[t]];
    const double* b = &xyz[3 * tri[t + 1]];
    const double* c = &xyz[3 * tri[t + 2]];
    vol += (long double)a[0] * ((long double)b[1] * c[2] - (long double)b[2] * c[1]) +
           (long double)a[1] * ((long double)b[2] * c[0] - (long double)b[0] * c[2]) +
           (long double)a[2] * ((long double)b[0] * c[1] - (long double)b[1] * c[0]);
  }
  return static_cast<double>(vol / 6);
}

/// Peak resident set size of this process in KiB.
inline long peak_rss_kib() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return u.ru_maxrss;
}

/// JSON string escaping for error messages.
inline std::string json_escape(const std::string& s) {
  std::string o;
  for (char c : s) {
    if (c == '"' || c == '\\') {
      o += '\\';
      o += c;
    } else if (static_cast<unsigned char>(c) < 0x20) {
      o += ' ';
    } else {
      o += c;
    }
  }
  return o;
}

inline std::string json_number(double x) {
  if (!std::isfinite(x)) return "null";
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.17g", x);
  return buf;
}

}  // namespace bench
