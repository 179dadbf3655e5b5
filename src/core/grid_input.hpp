#pragma once
// The operands on the integer grid: quantized, triangulated (triangulate.hpp),
// and audited for what the rounding did to them.
//
// The grid has 2^26 steps across the joint bounding box of all operands. A
// triangle whose features are finer than a step can collapse (become
// degenerate and vanish) or flip (reverse its orientation). A few such
// triangles in a large mesh are a local perturbation and only warned about;
// an operand that the grid erases or turns inside out (most of its triangles
// collapse or flip, typically a small operand beside a huge one) would give
// a wrong answer, so that is an ember::Error.
#include <array>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "ember/boolean.hpp"
#include "ember/core/quantize.hpp"

namespace ember::core {

struct GridTriangle {
  std::array<IntPoint, 3> p;
  std::array<std::uint32_t, 3> v;  ///< the corners' vertex indices in the operand's mesh
  std::uint32_t operand, face;
};

struct GridInput {
  std::vector<GridTriangle> triangles;    ///< operand by operand, faces in order
  std::vector<std::size_t> operand_begin;  ///< operand o's triangles: [begin[o], begin[o+1])
  std::array<std::int64_t, 3> lo{}, hi{};  ///< bounds of all grid vertices
};

/// Quantizes and triangulates every face of every operand with q.
GridInput to_grid(std::span<const Mesh> operands, const Quantizer& q);

/// Counts per operand the triangles the grid collapsed or flipped (into
/// reports[o].triangles / collapsed_triangles / flipped_triangles). Throws
/// ember::Error naming the operand, the counts and the grid step when an
/// operand lost most of itself; otherwise adds one warning per affected operand.
void audit_quantization(std::span<const Mesh> operands, const GridInput& grid, const Quantizer& q,
                        std::vector<OperandReport>& reports, std::vector<std::string>& warnings);

}  // namespace ember::core
