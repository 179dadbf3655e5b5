// STL, binary and ASCII. STL stores each triangle with its own three corners,
// so identical positions are welded here into shared vertices: later stages
// need an indexed mesh to tell whether the surface is closed.
#include <array>
#include <bit>
#include <cmath>
#include <cstring>
#include <limits>
#include <vector>

#include "ember/io/mesh_io.hpp"
#include "io/text_scanner.hpp"
#include "io/writer_support.hpp"

namespace ember {
namespace {

using io_detail::fail_at_offset;
using io_detail::fail_in_file;

/// Open-addressing hash from exact coordinate bit patterns to vertex index.
class VertexWelder {
 public:
  VertexWelder(Mesh& mesh, std::size_t expected) : mesh_(mesh) {
    std::size_t cap = 64;
    while (cap < 2 * expected) cap *= 2;
    slots_.assign(cap, kEmpty);
    mesh_.vertices.reserve(expected);
  }

  std::uint32_t index_of(Vec3d p) {
    // +0.0 and -0.0 are the same position; adding 0.0 turns -0.0 into +0.0.
    p.x += 0.0;
    p.y += 0.0;
    p.z += 0.0;
    if (2 * (mesh_.vertices.size() + 1) > slots_.size()) grow();
    const std::size_t mask = slots_.size() - 1;
    for (std::size_t i = hash(p) & mask;; i = (i + 1) & mask) {
      const std::uint32_t v = slots_[i];
      if (v == kEmpty) {
        slots_[i] = static_cast<std::uint32_t>(mesh_.vertices.size());
        mesh_.vertices.push_back(p);
        return slots_[i];
      }
      if (same(mesh_.vertices[v], p)) return v;
    }
  }

 private:
  static constexpr std::uint32_t kEmpty = std::numeric_limits<std::uint32_t>::max();

  static bool same(const Vec3d& a, const Vec3d& b) {
    return std::bit_cast<std::uint64_t>(a.x) == std::bit_cast<std::uint64_t>(b.x) &&
           std::bit_cast<std::uint64_t>(a.y) == std::bit_cast<std::uint64_t>(b.y) &&
           std::bit_cast<std::uint64_t>(a.z) == std::bit_cast<std::uint64_t>(b.z);
  }
  static std::size_t hash(const Vec3d& p) {
    std::uint64_t h = std::bit_cast<std::uint64_t>(p.x) * 0x9E3779B97F4A7C15ull;
    h ^= std::bit_cast<std::uint64_t>(p.y) * 0xC2B2AE3D27D4EB4Full;
    h ^= std::bit_cast<std::uint64_t>(p.z) * 0x165667B19E3779F9ull;
    return static_cast<std::size_t>(h ^ (h >> 31));
  }
  void grow() {
    std::vector<std::uint32_t> old(slots_.size() * 2, kEmpty);
    old.swap(slots_);
    const std::size_t mask = slots_.size() - 1;
    for (std::uint32_t v : old) {
      if (v == kEmpty) continue;
      std::size_t i = hash(mesh_.vertices[v]) & mask;
      while (slots_[i] != kEmpty) i = (i + 1) & mask;
      slots_[i] = v;
    }
  }

  Mesh& mesh_;
  std::vector<std::uint32_t> slots_;
};

std::uint32_t load_u32le(const char* p) {
  std::uint32_t v;
  std::memcpy(&v, p, 4);
  if constexpr (std::endian::native == std::endian::big) v = __builtin_bswap32(v);
  return v;
}

float load_f32le(const char* p) { return std::bit_cast<float>(load_u32le(p)); }

bool iequals(std::string_view a, std::string_view b) {
  if (a.size() != b.size()) return false;
  for (std::size_t i = 0; i < a.size(); ++i) {
    char c = a[i];
    if (c >= 'A' && c <= 'Z') c = static_cast<char>(c - 'A' + 'a');
    if (c != b[i]) return false;
  }
  return true;
}

/// ASCII STL starts with "solid" and is text; binary files may start with
/// "solid" too, but their float data soon contains control bytes.
bool looks_like_ascii(std::string_view bytes) {
  std::size_t i = 0;
  while (i < bytes.size() && io_detail::TextScanner::is_space(bytes[i])) ++i;
  if (bytes.size() - i < 5 || !iequals(bytes.substr(i, 5), "solid")) return false;
  const std::size_t n = std::min<std::size_t>(bytes.size(), 1024);
  for (std::size_t k = 0; k < n; ++k) {
    const auto c = static_cast<unsigned char>(bytes[k]);
    if (c < 0x20 && !io_detail::TextScanner::is_space(static_cast<char>(c))) return false;
    if (c == 0x7f) return false;
  }
  return true;
}

Mesh read_binary_stl(std::string_view bytes, std::string_view name) {
  const std::uint32_t n = load_u32le(bytes.data() + 80);
  Mesh mesh;
  mesh.indices.reserve(std::size_t{n} * 3);
  mesh.face_offsets.reserve(std::size_t{n} + 1);
  VertexWelder welder(mesh, n / 2 + 16);  // closed triangle meshes have ~n/2 vertices
  const char* base = bytes.data();
  for (std::uint32_t t = 0; t < n; ++t) {
    const std::size_t record = 84 + std::size_t{50} * t;
    std::uint32_t tri[3];
    for (int k = 0; k < 3; ++k) {
      const std::size_t at = record + 12 + 12 * static_cast<std::size_t>(k);
      const double x = load_f32le(base + at), y = load_f32le(base + at + 4), z = load_f32le(base + at + 8);
      if (!std::isfinite(x) || !std::isfinite(y) || !std::isfinite(z)) {
        const int axis = !std::isfinite(x) ? 0 : !std::isfinite(y) ? 1 : 2;
        fail_at_offset(name, at + 4 * static_cast<std::size_t>(axis),
                       "triangle " + std::to_string(t) + " corner " + std::to_string(k) + " has a non-finite " +
                           "xyz"[axis] + " coordinate");
      }
      tri[k] = welder.index_of({x, y, z});
    }
    mesh.indices.insert(mesh.indices.end(), tri, tri + 3);
    mesh.face_offsets.push_back(static_cast<std::uint32_t>(mesh.indices.size()));
  }
  return mesh;
}

class AsciiStlReader {
 public:
  AsciiStlReader(std::string_view bytes, std::string_view name, std::vector<std::string>* warnings)
      : s_(bytes, name, /*multiline=*/true, 0), welder_(mesh_, bytes.size() / 400 + 16), warnings_(warnings) {}

  Mesh read() {
    expect("solid");
    s_.next_line();  // the solid's name
    for (;;) {
      const std::string_view tok = s_.token();
      if (tok.empty()) {
        // Several exporters omit the closing line; the facets are complete
        // (a cut inside a facet is still an error), so read them and say so.
        if (warnings_)
          warnings_->push_back(std::string(s_.name()) + ": ASCII STL ends without 'endsolid' (line " +
                               std::to_string(s_.line()) + "); the file may be truncated after a complete facet");
        break;
      }
      if (iequals(tok, "facet")) {
        read_facet();
      } else if (iequals(tok, "endsolid")) {
        s_.next_line();
        if (s_.at_end()) break;
        expect("solid");  // several solids in one file
        s_.next_line();
      } else {
        s_.fail("expected 'facet' or 'endsolid', found " + io_detail::quote(tok));
      }
    }
    return std::move(mesh_);
  }

 private:
  void expect(std::string_view kw) {
    const std::string_view tok = s_.token();
    if (!iequals(tok, kw))
      s_.fail("expected '" + std::string(kw) + "', found " + (tok.empty() ? "end of file" : io_detail::quote(tok)));
  }
  void read_facet() {
    expect("normal");
    // The stored normal is not used (it is recomputed from positions where
    // needed), so its three values are skipped rather than validated.
    for (int k = 0; k < 3; ++k)
      if (s_.token().empty()) s_.fail("file ends inside a facet normal");
    expect("outer");
    expect("loop");
    face_.clear();
    for (;;) {
      const std::string_view tok = s_.token();
      if (iequals(tok, "vertex")) {
        Vec3d p;
        p.x = s_.real("vertex x coordinate");
        p.y = s_.real("vertex y coordinate");
        p.z = s_.real("vertex z coordinate");
        face_.push_back(welder_.index_of(p));
      } else if (iequals(tok, "endloop")) {
        break;
      } else {
        s_.fail("expected 'vertex' or 'endloop', found " +
                (tok.empty() ? std::string("end of file") : io_detail::quote(tok)));
      }
    }
    if (face_.size() < 3) s_.fail("facet has " + std::to_string(face_.size()) + " vertices (at least 3 needed)");
    expect("endfacet");
    mesh_.add_face(face_);
  }

  io_detail::TextScanner s_;
  Mesh mesh_;
  VertexWelder welder_;
  std::vector<std::string>* warnings_;
  std::vector<std::uint32_t> face_;
};

}  // namespace

Mesh read_stl(std::string_view bytes, std::string_view name, std::vector<std::string>* warnings) {
  // A byte-order mark only ever precedes text, never a binary header.
  if (looks_like_ascii(io_detail::skip_bom(bytes)))
    return AsciiStlReader(io_detail::skip_bom(bytes), name, warnings).read();
  if (bytes.size() < 84)
    fail_in_file(name, "not an STL file: " + std::to_string(bytes.size()) +
                           " bytes is too short for binary STL (84-byte minimum) and it is not ASCII STL");
  const std::uint32_t n = load_u32le(bytes.data() + 80);
  const std::uint64_t needed = 84 + std::uint64_t{50} * n;
  if (needed > bytes.size())
    fail_at_offset(name, 80,
                   "binary STL header declares " + std::to_string(n) + " triangles, which needs " +
                       std::to_string(needed) + " bytes, but the file has only " + std::to_string(bytes.size()) +
                       " bytes (truncated or not an STL file)");
  // Some exporters pad the file or append data after the triangles; the
  // triangles the header declares are complete, so read them and say so.
  if (needed < bytes.size() && warnings)
    warnings->push_back(std::string(name) + ": binary STL has " + std::to_string(bytes.size() - needed) +
                        " bytes after the " + std::to_string(n) + " triangles its header declares (byte " +
                        std::to_string(needed) + " on); they are ignored");
  return read_binary_stl(bytes, name);
}

std::string write_stl(const Mesh& mesh) {
  io_detail::check_mesh_for_writing(mesh, "STL");
  const std::size_t triangles = mesh.triangle_count();
  if (triangles > std::numeric_limits<std::uint32_t>::max())
    throw Error("cannot write STL: " + std::to_string(triangles) + " triangles exceed the format's 2^32-1 limit");
  std::string out(84 + 50 * triangles, '\0');
  const std::string_view header = "binary STL written by ember";
  std::memcpy(out.data(), header.data(), header.size());
  char* p = out.data() + 80;
  const auto put_u32 = [&p](std::uint32_t v) {
    if constexpr (std::endian::native == std::endian::big) v = __builtin_bswap32(v);
    std::memcpy(p, &v, 4);
    p += 4;
  };
  const auto put_f32 = [&](double v) {
    const float f = static_cast<float>(v);
    if (!std::isfinite(f))
      throw Error("cannot write STL: coordinate " + std::to_string(v) + " does not fit in a float");
    put_u32(std::bit_cast<std::uint32_t>(f));
  };
  put_u32(static_cast<std::uint32_t>(triangles));
  for (std::size_t f = 0; f < mesh.face_count(); ++f) {
    const auto face = mesh.face(f);
    for (std::size_t k = 1; k + 1 < face.size(); ++k) {
      const Vec3d& a = mesh.vertices[face[0]];
      const Vec3d& b = mesh.vertices[face[k]];
      const Vec3d& c = mesh.vertices[face[k + 1]];
      const double ux = b.x - a.x, uy = b.y - a.y, uz = b.z - a.z;
      const double vx = c.x - a.x, vy = c.y - a.y, vz = c.z - a.z;
      double nx = uy * vz - uz * vy, ny = uz * vx - ux * vz, nz = ux * vy - uy * vx;
      const double len = std::sqrt(nx * nx + ny * ny + nz * nz);
      if (len > 0 && std::isfinite(len)) {
        nx /= len;
        ny /= len;
        nz /= len;
      } else {
        nx = ny = nz = 0;  // degenerate triangle: no meaningful normal
      }
      put_f32(nx), put_f32(ny), put_f32(nz);
      for (const Vec3d* v : {&a, &b, &c}) put_f32(v->x), put_f32(v->y), put_f32(v->z);
      p += 2;  // attribute byte count stays 0
    }
  }
  return out;
}

std::size_t stl_degenerate_triangles(const Mesh& mesh) {
  auto f32 = [&](std::uint32_t v) {
    const Vec3d& p = mesh.vertices[v];
    return std::array<double, 3>{static_cast<float>(p.x), static_cast<float>(p.y), static_cast<float>(p.z)};
  };
  std::size_t degenerate = 0;
  for (std::size_t f = 0; f < mesh.face_count(); ++f) {
    const auto face = mesh.face(f);
    for (std::size_t k = 1; k + 1 < face.size(); ++k) {
      const auto a = f32(face[0]), b = f32(face[k]), c = f32(face[k + 1]);
      // In extended precision: a zero cross product is degenerate for sure; a
      // triangle that only nearly collapses may be missed (this is a warning count).
      using ld = long double;
      const ld ux = ld(b[0]) - a[0], uy = ld(b[1]) - a[1], uz = ld(b[2]) - a[2];
      const ld vx = ld(c[0]) - a[0], vy = ld(c[1]) - a[1], vz = ld(c[2]) - a[2];
      degenerate += uy * vz - uz * vy == 0 && uz * vx - ux * vz == 0 && ux * vy - uy * vx == 0;
    }
  }
  return degenerate;
}

}  // namespace ember
