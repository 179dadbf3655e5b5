#pragma once
// Stage 1 of the Boolean (boolean.cpp): the caller's meshes become grid
// triangles. Validation, one quantization map for all operands (fitted to
// the vertices that faces use), grid triangles with welded vertex ids, the
// audit of what the rounding did, closedness, and the non-degenerate
// triangles by id. Every step is parallel and its result independent of
// the split; run it inside the Boolean's task arena.
#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "core/input/input_triangles.hpp"
#include "core/input/quantize.hpp"
#include "core/model/input_topology.hpp"
#include "ember/boolean.hpp"

namespace ember::core {

struct PreparedInput {
  Quantizer quantizer;
  InputTriangles triangles;                ///< the non-degenerate grid triangles by id
  std::array<std::int64_t, 3> lo{}, hi{};  ///< bounds of all grid vertices
  std::vector<std::size_t> open_edges;     ///< per operand; 0: closed
  /// The welded vertex ids numbered across operands, for the output stage's
  /// weld and T-junction search; none when they do not fit 32 bits (the weld
  /// then sorts every corner).
  std::optional<InputTopology> topology;
  std::size_t input_triangles = 0;     ///< after fan triangulation, degenerate ones included
  std::vector<OperandReport> reports;  ///< per operand: triangles, what the grid did, open edges
  std::vector<std::string> warnings;
};

/// Throws ember::Error for invalid meshes, for an operand that the grid
/// erases or turns inside out, and for an open operand unless `allow_open`.
PreparedInput prepare_input(std::span<const Mesh> operands, bool allow_open);

/// "operand i": how the library names an operand in messages.
std::string operand_name(std::size_t i);

}  // namespace ember::core
