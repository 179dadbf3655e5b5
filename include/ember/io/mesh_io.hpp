#pragma once
// Reading and writing meshes in OBJ, STL (binary and ASCII), OFF, PLY, 3MF and glTF 2.0 (.gltf, .glb).
//
// Readers take the whole file as bytes; `name` only appears in error messages.
// Text headers may start with a UTF-8 byte-order mark.
// Every malformed input ends in an ember::Error naming the file and the line
// (text formats) or byte offset (binary formats) and what was wrong; a reader
// never returns a mesh that silently differs from the file.
#include <cstdint>
#include <filesystem>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "ember/mesh.hpp"

namespace ember {

enum class MeshFormat { Obj, Stl, Off, Ply, ThreeMf, Gltf, Glb };

/// Limits a reader applies before it builds a mesh, so that a small file
/// cannot ask for unbounded memory or time.
struct ReadOptions {
  /// 3MF: components let an object hold transformed copies of other
  /// objects, which may hold copies again, so a 1 KB file can describe
  /// billions of triangles. A file whose build items expand (all components
  /// resolved) to more than this many triangles, or object instances, is
  /// refused before lib3mf resolves them. CLI: --max-3mf-triangles.
  std::uint64_t max_3mf_triangles = 100'000'000;
  /// 3MF: a file whose build items expand to more than 1 million triangles
  /// is refused when that is more than this many times the triangles the
  /// file stores (copies of copies: a component bomb). CLI: --max-3mf-instancing.
  std::uint64_t max_3mf_instancing = 1000;
};

/// Format chosen by file extension (case-insensitive); throws ember::Error for
/// an unknown extension, listing the supported ones.
MeshFormat format_from_path(const std::filesystem::path& path);

/// Reads a mesh file; the format follows the extension (STL ASCII/binary and
/// PLY ascii/binary are told apart by content). A 3MF file must hold exactly
/// one object; use read_meshes for several.
Mesh read_mesh(const std::filesystem::path& path);
/// Reads every mesh of a file: one per build item of a 3MF file, the single
/// mesh of any other format.
std::vector<Mesh> read_meshes(const std::filesystem::path& path);
/// As above with limits for a 3MF file's component expansion.
std::vector<Mesh> read_meshes(const std::filesystem::path& path, const ReadOptions& options);
/// As above; tolerated oddities of the file (an ASCII STL without 'endsolid')
/// are appended to `warnings` as "FILE: what" instead of being an error.
Mesh read_mesh(const std::filesystem::path& path, std::vector<std::string>* warnings);
/// Writes a mesh; the format follows the extension (STL: binary, PLY: binary
/// little endian). Throws ember::Error when the file cannot be written.
void write_mesh(const Mesh& mesh, const std::filesystem::path& path);
/// As above with one Provenance per face (a Boolean result's): PLY stores it
/// as the face properties `operand` and `source_face`; the other formats have
/// no per-face data and leave it out. Empty: none written.
void write_mesh(const Mesh& mesh, const std::filesystem::path& path, std::span<const Provenance> provenance);

/// OBJ: polygons with (negative) indices in v, v/vt, v//vn, v/vt/vn form;
/// `usemtl` gives face groups; other statements are ignored.
/// `vt`/`vn` referenced by faces become per-corner "uv" and "normal"
/// properties; a reference past the file's vt/vn lines drops that property
/// (noted in `warnings` when given).
Mesh read_obj(std::string_view bytes, std::string_view name, std::vector<std::string>* warnings = nullptr);
/// STL, binary or ASCII (detected by size and content). STL stores a triangle
/// soup; identical positions are merged into one vertex (+0.0 == -0.0). An
/// ASCII file that ends without 'endsolid' is read (other tools write such
/// files) and noted in `warnings` when given.
Mesh read_stl(std::string_view bytes, std::string_view name, std::vector<std::string>* warnings = nullptr);
/// OFF with optional ST/C/N prefixes in the header and per-face colors.
Mesh read_off(std::string_view bytes, std::string_view name);
/// PLY ascii, binary_little_endian or binary_big_endian with any properties.
Mesh read_ply(std::string_view bytes, std::string_view name);
/// 3MF (through lib3mf): one mesh per build item, with the item's and its
/// components' transforms applied. Coordinates are taken as they are, in the
/// file's unit; colors, materials and other extensions are ignored.
std::vector<Mesh> read_3mf(std::string_view bytes, std::string_view name);
/// As above; a file that expands beyond `options`' limits is an ember::Error
/// that names the limits and how to raise them.
std::vector<Mesh> read_3mf(std::string_view bytes, std::string_view name, const ReadOptions& options);
/// glTF 2.0 through tinygltf, JSON (.gltf) or binary (.glb): the triangles
/// (triangle lists, strips and fans) of every mesh node of the default scene
/// with the node transforms applied, as one mesh; each primitive's material
/// becomes its faces' group, named by the material (Mesh::face_groups).
/// Points and lines are skipped; sparse accessors, non-float positions and
/// accessors that reach past their buffers are errors. Textures are not
/// decoded. From memory, external buffer files cannot be read (read the file
/// by path); by path they are read from the file's folder.
Mesh read_gltf(std::string_view bytes, std::string_view name, bool binary);
/// Reads in-memory bytes in the given format (3MF: exactly one object; warnings: as for read_stl).
Mesh read_mesh(std::string_view bytes, MeshFormat format, std::string_view name,
               std::vector<std::string>* warnings = nullptr);

/// OBJ with shortest round-trip decimal coordinates (reads back bit-exact).
std::string write_obj(const Mesh& mesh);
/// Binary STL: faces fan-triangulated, float coordinates, normals from positions.
std::string write_stl(const Mesh& mesh);
/// Triangles (of a fan triangulation) that STL's float32 coordinates make
/// degenerate: two corners equal or all three collinear after the rounding.
/// STL is a second rounding after ember's one rounding to double.
std::size_t stl_degenerate_triangles(const Mesh& mesh);
/// OFF with shortest round-trip decimal coordinates.
std::string write_off(const Mesh& mesh);
/// Binary little-endian PLY with double coordinates (reads back bit-exact).
/// With `provenance` (one per face; throws ember::Error otherwise) every face
/// also gets `property uint operand` and `property uint source_face`, which
/// read_ply and other readers skip or keep as they choose.
std::string write_ply(const Mesh& mesh, std::span<const Provenance> provenance = {});
/// 3MF with one object and one build item, unit millimeter; faces
/// fan-triangulated. lib3mf 1.x keeps coordinates as floats and writes them
/// with 6 decimals, so they move by up to 1e-6 (in mm: 1 nm) — fine for
/// printing; use OBJ, OFF or PLY for bit-exact results. The UUIDs 3MF
/// requires are derived from the content, so the same meshes always give the
/// same bytes.
std::string write_3mf(const Mesh& mesh);
/// 3MF with one object and build item per mesh (read back by read_3mf as
/// separate meshes, by the CLI as separate operands).
std::string write_3mf(std::span<const Mesh> meshes);
/// glTF 2.0, JSON with the buffer embedded (binary false) or GLB: one node,
/// one primitive per face group (a material named after the group), faces
/// fan-triangulated, positions as float32 (glTF has no doubles: use OBJ, OFF
/// or PLY for bit-exact results).
std::string write_gltf(const Mesh& mesh, bool binary);
std::string write_mesh(const Mesh& mesh, MeshFormat format, std::span<const Provenance> provenance = {});

}  // namespace ember
