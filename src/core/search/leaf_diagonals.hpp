#pragma once
// The diagonal extents (solid_proof.hpp's DiagonalExtent) of the triangles
// in each leaf of a TriangleTree (leaf_extents.hpp), for the broad phases'
// leaf pairs: the solid proof's contact search (contact_search.cpp; on a
// pile of slivers its pairs are a large part of the proof) and the solid
// path's partner search (solid_route.cpp).
#include <cstdint>
#include <limits>
#include <span>

#include "core/search/contact_triangle.hpp"
#include "core/search/leaf_extents.hpp"

namespace ember::core {

// A diagonal projection x +- y +- z of grid coordinates (|x| <= 2^25) is
// below 3 * 2^25 in magnitude: int32 holds it.
static_assert(3 * kCoordLimit < std::numeric_limits<std::int32_t>::max(), "diagonal projections must fit int32");

class LeafDiagonals : public LeafExtents<4> {
 public:
  LeafDiagonals() = default;  ///< no leaves (filled by assignment)
  /// Over a tree of contact triangles (item i: tris[i]).
  LeafDiagonals(const TriangleTree& tree, std::span<const ContactTriangle> tris) {
    fill(tree, [&](std::uint32_t item) { return diagonal_extent(tris[item].p()); });
  }
  /// Over a tree of grid triangles (item i: corners[i]): an operand's, built
  /// once with its tree for the proof and the solid path's partner search
  /// (OperandTrees).
  LeafDiagonals(const TriangleTree& tree, std::span<const std::array<IntPoint, 3>> corners) {
    fill(tree, [&](std::uint32_t item) { return diagonal_extent(corners[item]); });
  }
};

}  // namespace ember::core
