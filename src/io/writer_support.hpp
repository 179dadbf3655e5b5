#pragma once
// Shared by the writers: shortest round-trip number formatting and a check
// that the mesh is well-formed before any bytes are produced, so a broken
// mesh ends in an ember::Error instead of a file that other tools misread.
#include <charconv>
#include <cmath>
#include <cstdint>
#include <string>
#include <string_view>

#include "ember/error.hpp"
#include "ember/mesh.hpp"

namespace ember::io_detail {

/// Appends the shortest decimal that reads back to exactly `v`.
inline void append_real(std::string& out, double v) {
  char buf[32];
  auto r = std::to_chars(buf, buf + sizeof buf, v);
  out.append(buf, r.ptr);
}

/// "x y z\n" with round-trip precision (the vertex line of OBJ and OFF).
inline void append_xyz_line(std::string& out, const Vec3d& v) {
  append_real(out, v.x);
  out += ' ';
  append_real(out, v.y);
  out += ' ';
  append_real(out, v.z);
  out += '\n';
}

/// The shortest decimal that reads back to the same float (properties are floats).
inline void append_float(std::string& out, float v) {
  char buf[32];
  auto r = std::to_chars(buf, buf + sizeof buf, v);
  out.append(buf, r.ptr);
}

inline void append_uint(std::string& out, std::uint64_t v) {
  char buf[24];
  auto r = std::to_chars(buf, buf + sizeof buf, v);
  out.append(buf, r.ptr);
}

inline void check_mesh_for_writing(const Mesh& mesh, std::string_view format) {
  const auto fail = [&](const std::string& what) { throw Error("cannot write " + std::string(format) + ": " + what); };
  if (mesh.face_offsets.empty() || mesh.face_offsets.front() != 0) fail("face_offsets must start with 0");
  if (mesh.face_offsets.back() != mesh.indices.size())
    fail("face_offsets ends at " + std::to_string(mesh.face_offsets.back()) + " but there are " +
         std::to_string(mesh.indices.size()) + " indices");
  for (std::size_t f = 0; f < mesh.face_count(); ++f) {
    if (mesh.face_offsets[f + 1] < mesh.face_offsets[f] + 3)
      fail("face " + std::to_string(f) + " has fewer than 3 vertices");
  }
  // A nan or inf would be written as text no reader (ember's included) accepts.
  for (std::size_t v = 0; v < mesh.vertices.size(); ++v) {
    const Vec3d& p = mesh.vertices[v];
    if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z)) {
      std::string xyz;
      for (double c : {p.x, p.y, p.z}) {
        if (!xyz.empty()) xyz += ' ';
        append_real(xyz, c);
      }
      throw Error("cannot write " + std::string(format) + ": vertex " + std::to_string(v) + " (" + xyz +
                      ") has a non-finite coordinate; only finite coordinates can be written",
                  {.vertex = v});
    }
  }
  for (std::size_t i = 0; i < mesh.indices.size(); ++i) {
    if (mesh.indices[i] >= mesh.vertices.size())
      fail("index " + std::to_string(mesh.indices[i]) + " at position " + std::to_string(i) +
           " is out of range (mesh has " + std::to_string(mesh.vertices.size()) + " vertices)");
  }
  if (!mesh.face_groups.empty() && mesh.face_groups.size() != mesh.face_count())
    fail("face_groups has " + std::to_string(mesh.face_groups.size()) + " entries for " +
         std::to_string(mesh.face_count()) + " faces; give one per face or none");
  for (const MeshProperty& p : mesh.properties) {
    const std::size_t elements = p.per_corner ? mesh.indices.size() : mesh.vertices.size();
    if (p.width == 0 || p.values.size() != elements * p.width)
      fail("property '" + p.name + "' has " + std::to_string(p.values.size()) + " values for " +
           std::to_string(elements) + (p.per_corner ? " corners" : " vertices") + " of width " +
           std::to_string(p.width));
    for (const float v : p.values)
      if (!std::isfinite(v)) fail("property '" + p.name + "' has a non-finite value");
  }
  // A group name is written as one word (OBJ usemtl).
  for (const std::string& name : mesh.group_names)
    if (name.find_first_of(" \t\r\n\f\v#") != std::string::npos)
      fail("group name '" + name + "' holds white space or '#'; group names are written as one word");
}

}  // namespace ember::io_detail
