#pragma once
// The operands on the integer grid: quantized, triangulated (face_triangulation.hpp),
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

#include "core/support/fill_vector.hpp"
#include "ember/boolean.hpp"
#include "core/input/quantize.hpp"

namespace ember::core {

/// Where a grid triangle comes from.
struct GridTriangle {
  std::array<std::uint32_t, 3> v;  ///< the corners' vertex indices in the operand's mesh
  std::uint32_t operand, face;
};

/// Its per-triangle arrays are FillVectors (fill_vector.hpp): to_grid sizes
/// them, then writes every entry in parallel. The arrays that GridTriangles
/// keeps (corners, vertex ids, normals) are separate, so that
/// build_grid_triangles can move them there.
struct GridInput {
  FillVector<GridTriangle> triangles;           ///< operand by operand, faces in order
  FillVector<std::array<IntPoint, 3>> corners;  ///< per triangle, its grid corners
  /// Per triangle, its corners' welded grid vertex ids: within one operand,
  /// equal ids iff equal grid positions (numbered in sorted position order,
  /// so independent of scheduling). For edge matching (closedness, the
  /// proof's components).
  FillVector<std::array<std::uint32_t, 3>> vertex_ids;
  /// Per triangle, grid_normal of its corners (zero for one that collapsed
  /// on the grid): computed once here for the audit, the set-up's drop of
  /// degenerate triangles and, through GridTriangles::normals, the proof and
  /// the broad phases.
  FillVector<std::array<std::int64_t, 3>> normals;
  std::vector<std::size_t> operand_begin;  ///< operand o's triangles: [begin[o], begin[o+1])
  std::vector<std::size_t> vertex_count;   ///< per operand: how many welded ids it has
  std::array<std::int64_t, 3> lo{}, hi{};  ///< bounds of all grid vertices
};

/// Per operand, the indices of the vertices its faces use, increasing. The
/// operands must have passed validation (indices in range).
using UsedVertices = std::vector<FillVector<std::uint32_t>>;
UsedVertices used_vertices(std::span<const Mesh> operands);

/// The quantization map fitted to the vertices that faces use (the bounding
/// box of all operands together), computed in parallel. The operands must
/// have passed validation (indices in range, finite coordinates); `used` is
/// their used_vertices (computed once, shared with to_grid).
Quantizer fit_used_vertices(std::span<const Mesh> operands, const UsedVertices& used);

/// Below this many triangles in all, the set-up runs the operands' chains
/// (and the audit beside the edge matching) side by side: each chain is
/// serial steps and short loops that cannot fill the threads alone. Above
/// it their loops do (side by side gains no time), and one chain at a time
/// keeps the transient buffers to one
/// operand's, allocated by the calling thread.
inline constexpr std::size_t kSideBySideTriangles = std::size_t{1} << 17;
inline bool side_by_side(const GridInput& gi) { return gi.triangles.size() < kSideBySideTriangles; }

/// Quantizes, welds and triangulates every face of every operand with q, in
/// parallel (run it inside the Boolean's task arena). A face of n corners
/// becomes n - 2 triangles, so face f's triangles start at
/// face_offsets[f] - 2 f and the layout does not depend on scheduling.
/// `used`: the operands' used_vertices.
GridInput to_grid(std::span<const Mesh> operands, const Quantizer& q, const UsedVertices& used);

/// What the grid did to the input triangle (a, b, c) whose grid corners
/// have the grid normal g: -1 it had no area to begin with (|n| <= 2^-40
/// |b - a||c - a| for its normal n, evaluated in long double), 0 kept, 1
/// collapsed (g = 0), 2 flipped (n . g < 0). rounding_change_reference is
/// that definition in long double; rounding_change decides most triangles
/// in double, where it provably agrees, and falls back to it elsewhere.
int rounding_change(const Vec3d& a, const Vec3d& b, const Vec3d& c, const std::array<std::int64_t, 3>& g);
int rounding_change_reference(const Vec3d& a, const Vec3d& b, const Vec3d& c, const std::array<std::int64_t, 3>& g);

/// Counts per operand the triangles the grid collapsed or flipped (into
/// reports[o].triangles / collapsed_triangles / flipped_triangles). Throws
/// ember::Error naming the operand, the counts and the grid step when an
/// operand lost most of itself; otherwise adds one warning per affected operand.
void audit_quantization(std::span<const Mesh> operands, const GridInput& grid, const Quantizer& q,
                        std::vector<OperandReport>& reports, std::vector<std::string>& warnings);

}  // namespace ember::core
