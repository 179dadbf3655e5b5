#include "cli/operands.hpp"

#include "ember/error.hpp"
#include "ember/io/mesh_io.hpp"

namespace ember::cli {

Operands read_operands(const std::vector<std::string>& paths, std::vector<std::string>* warnings, std::string* activity,
                       const ReadOptions& options) {
  Operands out;
  for (const std::string& path : paths) {
    if (activity) *activity = "reading " + path;
    // 3MF files may hold several objects; the other formats hold one mesh and
    // may report tolerated oddities (an ASCII STL without 'endsolid').
    std::vector<Mesh> meshes;
    if (format_from_path(path) == MeshFormat::ThreeMf)
      meshes = read_meshes(path, options);
    else
      meshes.push_back(read_mesh(path, warnings));
    for (std::size_t i = 0; i < meshes.size(); ++i) {
      out.names.push_back(meshes.size() == 1 ? path
                                             : path + " (object " + std::to_string(i + 1) + " of " +
                                                   std::to_string(meshes.size()) + ")");
      // Every format can hold an empty mesh (a header with zero faces, an
      // OBJ of comments, a 3MF object without triangles); as an operand it is
      // almost always a failed export, so it is an error in every format alike.
      if (meshes[i].face_count() == 0)
        throw Error("has no faces (an empty mesh); every operand needs at least one face", {.file = out.names.back()});
      out.meshes.push_back(std::move(meshes[i]));
    }
  }
  return out;
}

}  // namespace ember::cli
