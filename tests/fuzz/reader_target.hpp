#pragma once
// One libFuzzer target per reader: each fuzz_<format>.cpp defines
// EMBER_FUZZ_FORMAT and includes this file. A reader must return a
// well-formed mesh (offsets consistent, every face with 3+ vertices, every
// index in range, finite coordinates) or throw ember::Error naming the file;
// anything else (another exception, a crash, a sanitizer report, a mesh that
// breaks these rules) aborts, which libFuzzer records as a finding.
//
// The same source builds with any compiler against replay_main.cpp, which
// feeds it files and folders: the suite runs that over a seed corpus, so the
// targets stay buildable and their checks run without clang.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <string>
#include <string_view>
#include <vector>

#include "ember/error.hpp"
#include "ember/io/mesh_io.hpp"

namespace ember::fuzz {

/// Why `m` is not well-formed, or nullptr when it is.
inline const char* mesh_defect(const Mesh& m) {
  if (m.face_offsets.empty() || m.face_offsets.front() != 0) return "face_offsets does not start with 0";
  if (m.face_offsets.back() != m.indices.size()) return "face_offsets does not end at the index count";
  for (std::size_t f = 0; f < m.face_count(); ++f)
    if (m.face_offsets[f + 1] < m.face_offsets[f] + 3) return "a face has fewer than 3 vertices";
  for (const std::uint32_t i : m.indices)
    if (i >= m.vertices.size()) return "an index is out of range";
  for (const Vec3d& v : m.vertices)
    if (!std::isfinite(v.x) || !std::isfinite(v.y) || !std::isfinite(v.z)) return "a coordinate is not finite";
  if (!m.face_groups.empty() && m.face_groups.size() != m.face_count()) return "face_groups is not one per face";
  for (const MeshProperty& p : m.properties)
    if (p.width == 0 || p.values.size() != p.width * (p.per_corner ? m.indices.size() : m.vertices.size()))
      return "a property's size does not match the mesh";
  for (const std::uint32_t g : m.face_groups)
    if (!m.group_names.empty() && g >= m.group_names.size()) return "a face group has no entry in group_names";
  return nullptr;
}

[[noreturn]] inline void finding(const std::string& what) {
  std::fprintf(stderr, "ember fuzz finding: %s\n", what.c_str());
  std::abort();
}

inline void check_reader(MeshFormat format, std::string_view bytes) {
  try {
    std::vector<Mesh> meshes;
    std::vector<std::string> warnings;
    if (format == MeshFormat::ThreeMf)
      meshes = read_3mf(bytes, "fuzz");
    else
      meshes.push_back(read_mesh(bytes, format, "fuzz", &warnings));
    for (const Mesh& m : meshes)
      if (const char* defect = mesh_defect(m)) finding(std::string("returned mesh: ") + defect);
    for (const std::string& w : warnings)
      if (w.rfind("fuzz", 0) != 0) finding("warning without the file name: " + w);
  } catch (const Error& e) {
    if (std::string_view(e.what()).rfind("fuzz", 0) != 0)
      finding(std::string("error without the file name: ") + e.what());
  } catch (const std::bad_alloc&) {
    // Allowed only where the input asks for it; the readers bound their
    // allocations by the input size, so this is a finding too.
    finding("std::bad_alloc");
  } catch (const std::exception& e) {
    finding(std::string("non-ember exception: ") + e.what());
  }
}

}  // namespace ember::fuzz

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  ember::fuzz::check_reader(EMBER_FUZZ_FORMAT, std::string_view(reinterpret_cast<const char*>(data), size));
  return 0;
}
