// Wavefront OBJ: `v` and `f` make the mesh and `usemtl` its face groups
// (Mesh::face_groups, named by material); every other statement of the format
// is recognised and skipped, and anything unrecognised is an error so that a
// non-OBJ file never reads as a silently empty mesh.
#include <algorithm>
#include <array>
#include <limits>
#include <vector>

#include "ember/io/mesh_io.hpp"
#include "io/text_scanner.hpp"
#include "io/writer_support.hpp"

namespace ember {
namespace {

bool is_ignored_statement(std::string_view kw) {
  static constexpr std::array<std::string_view, 39> kIgnored = {
      "vt",     "vn",   "vp",    "g",        "o",        "s",          "mtllib",    "l",      "p",   "maplib",
      "usemap", "lod",  "bevel", "c_interp", "d_interp", "shadow_obj", "trace_obj", "cstype", "deg", "bmat",
      "step",   "curv", "curv2", "surf",     "parm",     "trim",       "hole",      "scrv",   "sp",  "end",
      "con",    "mg",   "call",  "csh",      "ctech",    "stech",      "bsp",       "bzp",    "res"};
  return std::find(kIgnored.begin(), kIgnored.end(), kw) != kIgnored.end();
}

}  // namespace

Mesh read_obj(std::string_view bytes, std::string_view name) {
  bytes = io_detail::skip_bom(bytes);
  // Every other format rejects an empty file; an empty OBJ is most likely a
  // failed export, not an empty solid. (A file with only comments, as ember
  // writes for an empty result, stays a valid empty mesh.)
  if (bytes.find_first_not_of(" \t\r\n\f\v") == std::string_view::npos)
    io_detail::fail_in_file(name, "empty file: no faces in " + std::string(name));
  io_detail::TextScanner s(bytes, name, /*multiline=*/false, '#');
  Mesh mesh;
  mesh.vertices.reserve(bytes.size() / 64);
  mesh.indices.reserve(bytes.size() / 16);
  mesh.face_offsets.reserve(bytes.size() / 48);
  std::vector<std::uint32_t> face;
  // Positive indices are checked once the vertex count is final, because some
  // exporters write faces before the vertices they use.
  std::int64_t max_index = 0;
  std::size_t max_index_line = 0;
  // Per face its material's group; kNone before the first usemtl.
  constexpr std::uint32_t kNone = UINT32_MAX;
  std::uint32_t material = kNone;
  std::vector<std::uint32_t> groups;
  constexpr auto kMaxVertices = static_cast<std::size_t>(std::numeric_limits<std::uint32_t>::max());

  while (!s.at_end()) {
    const std::string_view kw = s.token();
    if (kw.empty()) {  // blank or comment line
      s.next_line();
      continue;
    }
    if (kw == "v") {
      Vec3d v;
      v.x = s.real("vertex x coordinate");
      v.y = s.real("vertex y coordinate");
      v.z = s.real("vertex z coordinate");
      // Allowed extras: a homogeneous w or an RGB color (some exporters).
      // They are not used, so a nan color does not make the mesh unreadable.
      for (int extra = 0; !s.at_line_end(); ++extra) {
        if (extra == 4) s.fail("vertex has more than 7 values");
        s.real("vertex value", /*finite_only=*/false);
      }
      if (mesh.vertices.size() >= kMaxVertices) s.fail("too many vertices (at most 2^32-1 supported)");
      mesh.vertices.push_back(v);
    } else if (kw == "f" || kw == "fo") {
      face.clear();
      while (!s.at_line_end()) {
        const std::int64_t i = s.integer("face index", '/');
        s.skip_token_rest();  // "/vt/vn" is not used
        if (i > 0) {
          if (i > static_cast<std::int64_t>(kMaxVertices)) s.fail("face index " + std::to_string(i) + " out of range");
          if (i > max_index) {
            max_index = i;
            max_index_line = s.line();
          }
          face.push_back(static_cast<std::uint32_t>(i - 1));
        } else if (i < 0) {
          const auto n = static_cast<std::int64_t>(mesh.vertices.size());
          // i < -n, not -i > n: negating INT64_MIN overflows.
          if (i < -n)
            s.fail("face index " + std::to_string(i) + " out of range (" + std::to_string(n) +
                   " vertices defined so far)");
          face.push_back(static_cast<std::uint32_t>(n + i));
        } else {
          s.fail("face index 0 is invalid (OBJ indices start at 1)");
        }
      }
      if (face.size() < 3) s.fail("face has " + std::to_string(face.size()) + " vertices (at least 3 needed)");
      if (mesh.indices.size() + face.size() > kMaxVertices) s.fail("too many face indices (at most 2^32-1 supported)");
      mesh.add_face(face);
      groups.push_back(material);
    } else if (kw == "usemtl") {
      const std::string_view name = s.token();
      if (name.empty()) s.fail("usemtl without a material name");
      const auto known = std::find(mesh.group_names.begin(), mesh.group_names.end(), name);
      material = static_cast<std::uint32_t>(known - mesh.group_names.begin());
      if (known == mesh.group_names.end()) mesh.group_names.emplace_back(name);
    } else if (!is_ignored_statement(kw)) {
      s.fail("unknown OBJ statement " + io_detail::quote(kw));
    }
    s.next_line();
  }
  if (max_index > static_cast<std::int64_t>(mesh.vertices.size()))
    io_detail::fail_at_line(name, max_index_line,
                            "face index " + std::to_string(max_index) + " out of range (file has " +
                                std::to_string(mesh.vertices.size()) + " vertices)");
  if (!mesh.group_names.empty()) {
    // Faces before the first usemtl form one more group, without a name.
    const auto unnamed = static_cast<std::uint32_t>(mesh.group_names.size());
    bool any_unnamed = false;
    for (std::uint32_t& g : groups)
      if (g == kNone) g = unnamed, any_unnamed = true;
    if (any_unnamed) mesh.group_names.emplace_back();
    mesh.face_groups = std::move(groups);
  }
  return mesh;
}

std::string write_obj(const Mesh& mesh) {
  io_detail::check_mesh_for_writing(mesh, "OBJ");
  std::string out;
  out.reserve(mesh.vertices.size() * 64 + mesh.indices.size() * 8 + mesh.face_count() * 3 + 32);
  out += "# written by ember\n";
  for (const Vec3d& v : mesh.vertices) {
    out += "v ";
    io_detail::append_xyz_line(out, v);
  }
  for (std::size_t f = 0; f < mesh.face_count(); ++f) {
    // A face group becomes a material: its name, or "group_G" for an unnamed one.
    if (!mesh.face_groups.empty() && (f == 0 || mesh.face_groups[f] != mesh.face_groups[f - 1])) {
      const std::uint32_t g = mesh.face_groups[f];
      out += "usemtl ";
      if (g < mesh.group_names.size() && !mesh.group_names[g].empty())
        out += mesh.group_names[g];
      else
        out += "group_" + std::to_string(g);
      out += '\n';
    }
    out += 'f';
    for (std::uint32_t i : mesh.face(f)) {
      out += ' ';
      io_detail::append_uint(out, std::uint64_t{i} + 1);
    }
    out += '\n';
  }
  return out;
}

}  // namespace ember
