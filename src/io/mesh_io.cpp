// File-level entry points: choose the format by extension, read the whole
// file into memory (the parsers work on one contiguous buffer) and write.
#include <sys/stat.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <memory>
#include <utility>

#include "ember/error.hpp"
#include "ember/io/mesh_io.hpp"
#include "io/gltf.hpp"

namespace ember {
namespace {

struct FileCloser {
  void operator()(std::FILE* f) const { std::fclose(f); }
};
using File = std::unique_ptr<std::FILE, FileCloser>;

std::string read_file(const std::filesystem::path& path) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) throw Error(path.string() + ": is a directory, not a mesh file");
  File f(std::fopen(path.c_str(), "rb"));
  if (!f) throw Error(path.string() + ": cannot open for reading: " + std::strerror(errno));
  // After following symlinks: a device such as /dev/zero never ends and would
  // be read until memory runs out. Pipes and FIFOs end when the writer closes.
  struct stat st {};
  if (::fstat(::fileno(f.get()), &st) == 0 && !S_ISREG(st.st_mode) && !S_ISFIFO(st.st_mode)) {
    const char* kind = S_ISCHR(st.st_mode)    ? "a character device"
                       : S_ISBLK(st.st_mode)  ? "a block device"
                       : S_ISSOCK(st.st_mode) ? "a socket"
                                              : "neither a regular file nor a pipe";
    throw Error("is " + std::string(kind) + ", not a mesh file; give a regular file, a pipe or a FIFO",
                {.file = path.string()});
  }
  std::string data;
  char buf[1 << 16];
  // Size from the file when known, so large files are read with one allocation.
  const auto size = std::filesystem::file_size(path, ec);
  if (!ec) data.reserve(static_cast<std::size_t>(size));
  for (;;) {
    const std::size_t got = std::fread(buf, 1, sizeof buf, f.get());
    data.append(buf, got);
    if (got < sizeof buf) break;
  }
  if (std::ferror(f.get())) throw Error(path.string() + ": read error: " + std::strerror(errno));
  return data;
}

/// read_mesh returns one mesh; a 3MF file may hold several (one per build item).
Mesh single_3mf_object(std::vector<Mesh> meshes, std::string_view name) {
  if (meshes.size() == 1) return std::move(meshes.front());
  throw Error(std::string(name) + ": the 3MF file holds " + std::to_string(meshes.size()) +
              " objects (build items), not one; read them with read_meshes (the CLI takes each as an operand)");
}

}  // namespace

MeshFormat format_from_path(const std::filesystem::path& path) {
  std::string ext = path.extension().string();
  for (char& c : ext)
    if (c >= 'A' && c <= 'Z') c = static_cast<char>(c - 'A' + 'a');
  if (ext == ".obj") return MeshFormat::Obj;
  if (ext == ".stl") return MeshFormat::Stl;
  if (ext == ".off") return MeshFormat::Off;
  if (ext == ".ply") return MeshFormat::Ply;
  if (ext == ".3mf") return MeshFormat::ThreeMf;
  if (ext == ".gltf") return MeshFormat::Gltf;
  if (ext == ".glb") return MeshFormat::Glb;
  throw Error(path.string() + ": unknown mesh file extension '" + path.extension().string() +
              "' (supported: .obj, .stl, .off, .ply, .3mf, .gltf, .glb)");
}

Mesh read_mesh(std::string_view bytes, MeshFormat format, std::string_view name, std::vector<std::string>* warnings) {
  switch (format) {
    case MeshFormat::Obj: return read_obj(bytes, name, warnings);
    case MeshFormat::Stl: return read_stl(bytes, name, warnings);
    case MeshFormat::Off: return read_off(bytes, name);
    case MeshFormat::Ply: return read_ply(bytes, name);
    case MeshFormat::ThreeMf: return single_3mf_object(read_3mf(bytes, name), name);
    case MeshFormat::Gltf: return read_gltf(bytes, name, false);
    case MeshFormat::Glb: return read_gltf(bytes, name, true);
  }
  throw Error(std::string(name) + ": invalid mesh format value");
}

Mesh read_mesh(const std::filesystem::path& path) { return read_mesh(path, nullptr); }

Mesh read_mesh(const std::filesystem::path& path, std::vector<std::string>* warnings) {
  const MeshFormat format = format_from_path(path);
  const std::string data = read_file(path);
  if (format == MeshFormat::Gltf || format == MeshFormat::Glb)  // external buffers beside the file
    return io_detail::read_gltf(data, path.string(), format == MeshFormat::Glb,
                                std::filesystem::absolute(path).parent_path(), ReadOptions{}.max_3mf_triangles);
  return read_mesh(data, format, path.string(), warnings);
}

std::vector<Mesh> read_meshes(const std::filesystem::path& path) { return read_meshes(path, ReadOptions{}); }

std::vector<Mesh> read_meshes(const std::filesystem::path& path, const ReadOptions& options) {
  const MeshFormat format = format_from_path(path);
  const std::string data = read_file(path);
  if (format == MeshFormat::ThreeMf) return read_3mf(data, path.string(), options);
  std::vector<Mesh> meshes;
  if (format == MeshFormat::Gltf || format == MeshFormat::Glb) {
    meshes.push_back(io_detail::read_gltf(data, path.string(), format == MeshFormat::Glb,
                                          std::filesystem::absolute(path).parent_path(), options.max_3mf_triangles));
    return meshes;
  }
  meshes.push_back(read_mesh(data, format, path.string()));
  return meshes;
}

std::string write_mesh(const Mesh& mesh, MeshFormat format, std::span<const Provenance> provenance) {
  switch (format) {
    case MeshFormat::Obj: return write_obj(mesh);
    case MeshFormat::Stl: return write_stl(mesh);
    case MeshFormat::Off: return write_off(mesh);
    case MeshFormat::Ply: return write_ply(mesh, provenance);
    case MeshFormat::ThreeMf: return write_3mf(mesh);
    case MeshFormat::Gltf: return write_gltf(mesh, false);
    case MeshFormat::Glb: return write_gltf(mesh, true);
  }
  throw Error("invalid mesh format value");
}

void write_mesh(const Mesh& mesh, const std::filesystem::path& path) { write_mesh(mesh, path, {}); }

void write_mesh(const Mesh& mesh, const std::filesystem::path& path, std::span<const Provenance> provenance) {
  std::string data;
  try {
    data = write_mesh(mesh, format_from_path(path), provenance);
  } catch (const Error& e) {
    // Name the file, keeping the fields (vertex, face) of the problem.
    if (!e.where().file.empty()) throw;
    ErrorLocation where = e.where();
    where.file = path.string();
    throw Error(e.problem(), where);
  }
  File f(std::fopen(path.c_str(), "wb"));
  if (!f) throw Error(path.string() + ": cannot open for writing: " + std::strerror(errno));
  if (std::fwrite(data.data(), 1, data.size(), f.get()) != data.size())
    throw Error(path.string() + ": write failed: " + std::strerror(errno));
  // fclose flushes; a failure there (e.g. disk full) is a failed write too.
  if (std::fclose(f.release()) != 0) throw Error(path.string() + ": write failed: " + std::strerror(errno));
}

}  // namespace ember
