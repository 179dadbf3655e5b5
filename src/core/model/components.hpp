#pragma once
// Connected components of grid triangles across their manifold edges.
#include <cstddef>
#include <cstdint>
#include <span>

#include "core/model/grid_triangles.hpp"

namespace ember::core {

/// Components of the triangles with keep[i], joined across their manifold
/// edges (GridTriangles::neighbors, both ends kept): per kept triangle the
/// smallest id of its component (other entries unspecified). Shared by the
/// proof's components and the solid path's untouched ones.
FillVector<std::uint32_t> neighbour_components(const GridTriangles& grid, std::span<const char> keep);
/// The same for all triangles first .. first + count - 1 (an operand's range
/// of ids) and the manifold edges between them: entry i is triangle first +
/// i's. Linear in count, not in all triangles.
FillVector<std::uint32_t> neighbour_components(const GridTriangles& grid, std::uint32_t first, std::size_t count);

}  // namespace ember::core
