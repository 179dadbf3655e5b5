#pragma once
// The mesh stage: turns the core's exact output polygons (a soup of convex
// pieces with T-junctions) into an indexed triangle mesh that is closed
// wherever the exact result is closed.
//
//  1. exact_weld:   one id per exact point (equal points, however represented,
//                   share it); each id is rounded to double once.
//  2. tjunctions:   every vertex lying in the open interior of a polygon edge
//                   is inserted into that edge (exact incidence tests).
//  2b. pass_through: whole input triangles that gained no vertex and share no
//                   edge with a piece of their oriented plane go straight to
//                   the output (steps 3-4 would give them back unchanged).
//  3. regions:      pieces in the same oriented plane that share an edge are
//                   merged (their common edges cancel); a boundary vertex that
//                   only joins collinear edges between the same two regions is
//                   removed on both sides.
//  4. triangulate:  every region (outer loop + holes) is ear-clipped with exact
//                   orientation tests in its plane's projection.
// Everything is decided on exact points; no epsilon anywhere.
#include <array>
#include <atomic>
#include <cstdint>
#include <functional>
#include <span>
#include <vector>

#include "core/support/fill_vector.hpp"
#include "core/model/output_polygon.hpp"
#include "ember/boolean.hpp"
#include "core/input/quantize.hpp"
#include "core/output/output_vertices.hpp"

namespace ember::core {

/// Twice the area vector of a face of rounded (double) vertices, summed from
/// differences to its first vertex in extended precision, is exactly zero.
/// Shared by the mesh stage (rounded_degenerate) and the polygon export (slivers).
bool rounded_area_is_zero(const std::vector<Vec3d>& pos, std::span<const std::uint32_t> face);

/// The indexed mesh of `tris` (vertex ids below vertex_count): vertices
/// numbered by first use (as a serial pass along the triangles would, in
/// parallel), each placed at position(id); the triangles from `whole_count`
/// on (the first ones are whole input triangles, whose rounded area is
/// known) are counted in `rounded_degenerate` when their rounded corners
/// have zero area. Shared by the mesh stage and the direct route
/// (direct_mesh.hpp).
void write_indexed_mesh(std::span<const std::array<std::uint32_t, 3>> tris, std::size_t vertex_count,
                        const std::function<Vec3d(std::uint32_t)>& position, std::size_t whole_count, Mesh& mesh,
                        std::size_t& rounded_degenerate);

struct MeshOutputStats {
  std::size_t tjunctions = 0;         ///< vertices inserted into edges
  std::size_t collinear_removed = 0;  ///< boundary vertices removed on both sides
  std::size_t regions = 0;
  std::size_t fallback_regions = 0;    ///< regions triangulated piece by piece
  std::size_t rounded_degenerate = 0;  ///< triangles whose rounded corners have zero area
  double weld_ms = 0, tjunction_ms = 0, regions_ms = 0, triangulate_ms = 0;  ///< time per step
};

struct MeshOutput {
  Mesh mesh;
  std::vector<Provenance> provenance;
  MeshOutputStats stats;
};

/// Steps 1-4. `sources[id]` is the provenance of source polygon id; `ids`
/// (optional) speeds up step 1; `source_groups` (optional, per source id)
/// keeps coplanar pieces of different face groups in different regions.
MeshOutput build_triangle_mesh(std::span<const OutputPolygon> polys, const Quantizer& q,
                               std::span<const Provenance> sources, const InputTopology* ids = nullptr,
                               std::span<const std::uint32_t> source_groups = {});

}  // namespace ember::core
