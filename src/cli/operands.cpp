#include "cli/operands.hpp"

#include "ember/io/mesh_io.hpp"

namespace ember::cli {

Operands read_operands(const std::vector<std::string>& paths) {
  Operands out;
  for (const std::string& path : paths) {
    std::vector<Mesh> meshes = read_meshes(path);
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
