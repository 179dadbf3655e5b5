#include "cli/operands.hpp"

#include "ember/io/mesh_io.hpp"

namespace ember::cli {

Operands read_operands(const std::vector<std::string>& paths, std::vector<std::string>* warnings) {
  Operands out;
  for (const std::string& path : paths) {
    // 3MF files may hold several objects; the other formats hold one mesh and
    // may report tolerated oddities (an ASCII STL without 'endsolid').
    std::vector<Mesh> meshes;
    if (format_from_path(path) == MeshFormat::ThreeMf)
      meshes = read_meshes(path);
    else
      meshes.push_back(read_mesh(path, warnings));
    for (std::size_t i = 0; i < meshes.size(); ++i) {
      out.names.push_back(meshes.size() == 1 ? path
                                             : path + " (object " + std::to_string(i + 1) + " of " +
                                                   std::to_string(meshes.size()) + ")");
      out.meshes.push_back(std::move(meshes[i]));
    }
  }
  return out;
}

}  // namespace ember::cli
