#pragma once
// The CLI's operands: every input file gives one mesh, except a 3MF file with
// several objects (build items), which gives one operand per object.
#include <string>
#include <vector>

#include "ember/io/mesh_io.hpp"
#include "ember/mesh.hpp"

namespace ember::cli {

struct Operands {
  std::vector<Mesh> meshes;
  /// Per mesh, how the user knows it: the path, or "path (object i of n)".
  std::vector<std::string> names;
};

/// Reads every path; an operand without faces is an ember::Error naming it.
/// `activity`, when given, is set to "reading PATH" before each file is read
/// (for the out-of-memory message).
Operands read_operands(const std::vector<std::string>& paths, std::vector<std::string>* warnings = nullptr,
                       std::string* activity = nullptr, const ReadOptions& options = {});

}  // namespace ember::cli
