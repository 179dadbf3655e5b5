// OFF (Object File Format). Header "[ST][C][N]OFF", then "nv nf ne", then one
// vertex per line (extra values such as colors or normals follow x y z and are
// skipped), then one face per line: "n i0 .. in-1" optionally followed by a
// color. Comments start with '#'.
#include <algorithm>
#include <limits>
#include <vector>

#include "ember/io/mesh_io.hpp"
#include "io/text_scanner.hpp"
#include "io/writer_support.hpp"

namespace ember {

Mesh read_off(std::string_view bytes, std::string_view name) {
  bytes = io_detail::skip_bom(bytes);
  io_detail::TextScanner s(bytes, name, /*multiline=*/true, '#');
  // Values of one vertex or face must stay on its line: a short line would
  // otherwise borrow values from the next one and shift everything after it.
  const auto on_line = [&s](const char* what) {
    if (!s.more_on_line()) s.fail(std::string("expected ") + what + ", found end of line");
  };

  std::string_view header = s.token();
  if (header.empty()) s.fail("empty file, expected an OFF header");
  std::string_view kw = header;
  for (std::string_view prefix : {"ST", "C", "N"})
    if (kw.starts_with(prefix)) kw.remove_prefix(prefix.size());
  if (kw.starts_with("4OFF") || kw.starts_with("nOFF"))
    s.fail("OFF header " + io_detail::quote(header) + ": only 3D OFF is supported");
  // Some writers glue the counts to the keyword ("OFF8 6 12"): re-read them.
  if (kw.size() > 3 && kw.starts_with("OFF") && kw[3] >= '0' && kw[3] <= '9') {
    s.set_position(kw.data() + 3);
    kw = kw.substr(0, 3);
  }
  if (kw != "OFF") s.fail("expected an OFF header such as 'OFF' or 'COFF', found " + io_detail::quote(header));
  if (s.accept("BINARY")) s.fail("binary OFF is not supported");

  const std::int64_t nv = s.integer("vertex count");
  const std::int64_t nf = s.integer("face count");
  // The edge count is unused, and some writers leave it out.
  const std::int64_t ne = s.more_on_line() ? s.integer("edge count") : 0;
  if (nv < 0 || nf < 0 || ne < 0) s.fail("negative count in the OFF header");
  // Every vertex needs at least 6 bytes ("0 0 0\n") and every face 8, so larger
  // counts are a broken header; checking first keeps allocations bounded.
  if (nv > static_cast<std::int64_t>(std::numeric_limits<std::uint32_t>::max()) ||
      static_cast<std::uint64_t>(nv) * 6 > s.remaining() + 6 || static_cast<std::uint64_t>(nf) * 8 > s.remaining() + 8)
    s.fail("OFF header declares " + std::to_string(nv) + " vertices and " + std::to_string(nf) +
           " faces, more than the remaining " + std::to_string(s.remaining()) + " bytes can hold");
  s.next_line();

  Mesh mesh;
  mesh.vertices.resize(static_cast<std::size_t>(nv));
  for (std::int64_t v = 0; v < nv; ++v) {
    if (s.at_end())
      s.fail("file ends after " + std::to_string(v) + " of the " + std::to_string(nv) +
             " vertices the header declares");
    Vec3d& p = mesh.vertices[static_cast<std::size_t>(v)];
    p.x = s.real("vertex x coordinate");
    on_line("vertex y coordinate");
    p.y = s.real("vertex y coordinate");
    on_line("vertex z coordinate");
    p.z = s.real("vertex z coordinate");
    s.next_line();
  }
  mesh.face_offsets.reserve(static_cast<std::size_t>(nf) + 1);
  mesh.indices.reserve(static_cast<std::size_t>(nf) * 3);
  for (std::int64_t f = 0; f < nf; ++f) {
    if (s.at_end())
      s.fail("file ends after " + std::to_string(f) + " of the " + std::to_string(nf) + " faces the header declares");
    const std::int64_t n = s.integer("face vertex count");
    if (n < 3) s.fail("face has " + std::to_string(n) + " vertices (at least 3 needed)");
    if (static_cast<std::uint64_t>(n) * 2 > s.remaining())
      s.fail("face declares " + std::to_string(n) + " vertices, more than the rest of the file holds");
    for (std::int64_t k = 0; k < n; ++k) {
      on_line("face index");
      const std::int64_t i = s.integer("face index");
      if (i < 0 || i >= nv)
        s.fail("face index " + std::to_string(i) + " out of range (file has " + std::to_string(nv) + " vertices)");
      mesh.indices.push_back(static_cast<std::uint32_t>(i));
    }
    if (mesh.indices.size() > std::numeric_limits<std::uint32_t>::max()) s.fail("too many face indices");
    mesh.face_offsets.push_back(static_cast<std::uint32_t>(mesh.indices.size()));
    s.next_line();  // an optional per-face color
  }
  // Data after the declared faces is ignored, as other OFF readers (CGAL,
  // libigl) do: the header counts define the mesh. (CGAL's own prim.off has
  // such an extra face line.)
  return mesh;
}

std::string write_off(const Mesh& mesh) {
  io_detail::check_mesh_for_writing(mesh, "OFF");
  std::string out;
  out.reserve(mesh.vertices.size() * 64 + mesh.indices.size() * 8 + mesh.face_count() * 4 + 32);
  out += "OFF\n";
  io_detail::append_uint(out, mesh.vertices.size());
  out += ' ';
  io_detail::append_uint(out, mesh.face_count());
  out += " 0\n";
  for (const Vec3d& v : mesh.vertices) io_detail::append_xyz_line(out, v);
  for (std::size_t f = 0; f < mesh.face_count(); ++f) {
    io_detail::append_uint(out, mesh.face_size(f));
    for (std::uint32_t i : mesh.face(f)) {
      out += ' ';
      io_detail::append_uint(out, i);
    }
    out += '\n';
  }
  return out;
}

}  // namespace ember
