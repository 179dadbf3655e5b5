// Wavefront OBJ: `v` and `f` make the mesh, `vt`/`vn` with `f v/vt/vn` its
// per-corner "uv" and "normal" properties, `usemtl` its face groups (named by
// material); every other statement of the format is recognised and skipped,
// and anything unrecognised is an error so that a non-OBJ file never reads as
// a silently empty mesh.
#include <algorithm>
#include <array>
#include <charconv>
#include <limits>
#include <vector>

#include "ember/io/mesh_io.hpp"
#include "io/text_scanner.hpp"
#include "io/writer_support.hpp"

namespace ember {
namespace {

bool is_ignored_statement(std::string_view kw) {
  static constexpr std::array<std::string_view, 37> kIgnored = {
      "vp",    "g",        "o",        "s",          "mtllib",    "l",      "p",   "maplib", "usemap", "lod",
      "bevel", "c_interp", "d_interp", "shadow_obj", "trace_obj", "cstype", "deg", "bmat",   "step",   "curv",
      "curv2", "surf",     "parm",     "trim",       "hole",      "scrv",   "sp",  "end",    "con",    "mg",
      "call",  "csh",      "ctech",    "stech",      "bsp",       "bzp",    "res"};
  return std::find(kIgnored.begin(), kIgnored.end(), kw) != kIgnored.end();
}

/// The "/vt/vn" after a face's vertex index: each part absent (0) or an index.
bool parse_refs(std::string_view rest, std::int64_t& vt, std::int64_t& vn) {
  vt = vn = 0;
  if (rest.empty()) return true;
  if (rest[0] != '/') return false;
  rest.remove_prefix(1);
  const auto number = [](std::string_view& s, std::int64_t& out) {
    if (s.empty() || s[0] == '/') return true;
    const auto [q, ec] = std::from_chars(s.data(), s.data() + s.size(), out);
    if (ec != std::errc() || out == 0) return false;
    s.remove_prefix(static_cast<std::size_t>(q - s.data()));
    return true;
  };
  if (!number(rest, vt)) return false;
  if (rest.empty()) return true;
  if (rest[0] != '/') return false;
  rest.remove_prefix(1);
  return number(rest, vn) && rest.empty();
}

/// A vt/vn reference resolved to a 0-based index (negative: relative to the
/// `count` defined so far); -1 when absent. Positive ones are checked at the end.
std::int64_t resolve(std::int64_t i, std::size_t count) {
  if (i > 0) return i - 1;
  if (i < 0) return i < -static_cast<std::int64_t>(count) ? INT64_MAX : static_cast<std::int64_t>(count) + i;
  return -1;
}

}  // namespace

Mesh read_obj(std::string_view bytes, std::string_view name, std::vector<std::string>* warnings) {
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
  std::vector<float> uvs, normals;                 // vt (u, v) and vn (x, y, z) as defined
  std::vector<std::int64_t> corner_uv, corner_nv;  // per corner: an index into them, or -1
  std::int64_t vt_ref = 0, vn_ref = 0;
  bool corner_refs = false;  // some corner had a vt or vn
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
        if (!parse_refs(s.token_rest(), vt_ref, vn_ref))
          s.fail("malformed face corner (expected v, v/vt, v//vn or v/vt/vn)");
        // Per-corner references are kept only once a file has one (most have none).
        if ((vt_ref || vn_ref) && !corner_refs) {
          corner_refs = true;
          corner_uv.assign(mesh.indices.size() + face.size(), -1);
          corner_nv.assign(mesh.indices.size() + face.size(), -1);
        }
        if (corner_refs) {
          corner_uv.push_back(resolve(vt_ref, uvs.size() / 2));
          corner_nv.push_back(resolve(vn_ref, normals.size() / 3));
          if (corner_uv.back() == INT64_MAX || corner_nv.back() == INT64_MAX)
            s.fail("texture or normal index out of range");
        }
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
    } else if (kw == "vt") {
      uvs.push_back(static_cast<float>(s.real("texture u")));
      uvs.push_back(s.at_line_end() ? 0.0f : static_cast<float>(s.real("texture v")));
    } else if (kw == "vn") {
      for (const char* what : {"normal x", "normal y", "normal z"}) normals.push_back(static_cast<float>(s.real(what)));
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
  // Corners with vt (vn) give the mesh a per-corner "uv" ("normal"); corners
  // without one get zeros. A reference past the file's vt (vn) lines drops
  // that property, with a warning: the geometry is intact, the property not.
  const auto corner_property = [&](const char* property, std::uint32_t width, const std::vector<float>& values,
                                   const std::vector<std::int64_t>& refs) {
    if (refs.size() != mesh.indices.size() ||
        std::all_of(refs.begin(), refs.end(), [](std::int64_t r) { return r < 0; }))
      return;
    MeshProperty p{property, width, true, std::vector<float>(refs.size() * width, 0.0f)};
    for (std::size_t c = 0; c < refs.size(); ++c) {
      if (refs[c] < 0) continue;
      if (static_cast<std::size_t>(refs[c]) >= values.size() / width) {
        const bool texture = property == std::string("uv");
        if (warnings)
          warnings->push_back(std::string(name) + ": " + (texture ? "texture" : "normal") + " index " +
                              std::to_string(refs[c] + 1) + " out of range (file has " +
                              std::to_string(values.size() / width) + "); " +
                              (texture ? "texture coordinates" : "normals") + " dropped");
        return;
      }
      std::copy_n(values.begin() + refs[c] * width, width, p.values.begin() + static_cast<std::ptrdiff_t>(c * width));
    }
    mesh.properties.push_back(std::move(p));
  };
  corner_property("uv", 2, uvs, corner_uv);
  corner_property("normal", 3, normals, corner_nv);
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
  // "uv" (width 2) and "normal" (width 3) as vt/vn lines, one per corner or
  // vertex as the property is; other properties have no OBJ form.
  const MeshProperty *uv = nullptr, *normal = nullptr;
  for (const MeshProperty& p : mesh.properties) {
    if (p.name == "uv" && p.width == 2) uv = &p;
    if (p.name == "normal" && p.width == 3) normal = &p;
  }
  for (const MeshProperty* p : {uv, normal}) {
    if (!p) continue;
    for (std::size_t e = 0; e < p->values.size() / p->width; ++e) {
      out += p == uv ? "vt" : "vn";
      for (std::uint32_t c = 0; c < p->width; ++c) {
        out += ' ';
        io_detail::append_float(out, p->values[e * p->width + c]);
      }
      out += '\n';
    }
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
    for (std::size_t k = 0; k < mesh.face_size(f); ++k) {
      const std::uint32_t i = mesh.face(f)[k];
      const std::size_t corner = mesh.face_offsets[f] + k;
      out += ' ';
      io_detail::append_uint(out, std::uint64_t{i} + 1);
      if (uv || normal) out += '/';
      if (uv) io_detail::append_uint(out, (uv->per_corner ? corner : i) + std::uint64_t{1});
      if (normal) {
        out += '/';
        io_detail::append_uint(out, (normal->per_corner ? corner : i) + std::uint64_t{1});
      }
    }
    out += '\n';
  }
  return out;
}

}  // namespace ember
