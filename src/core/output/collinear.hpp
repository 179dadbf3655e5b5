#pragma once
// Step 3b of the mesh stage (mesh_output.hpp): boundary vertices that only join collinear edges.
#include <array>
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "core/output/output_vertices.hpp"
#include "core/output/regions.hpp"

namespace ember::core {

/// One removal of step 3b: vertex v spliced out of edges in_1 (region 1) and
/// in_2 (region 2), killing out_1 and out_2.
struct Removal {
  std::uint32_t v, in_1, out_1, in_2, out_2;
};

/// Step 3 (collinear vertices). Returns the removals in the order made.
/// Vertices flagged in `pinned` (corners of step 2b's triangles, whose
/// edges the regions do not see) are kept.
std::vector<Removal> remove_collinear_vertices(Regions& regions, std::size_t vertex_count,
                                               const std::vector<char>& pinned);

/// Puts back every removal that touches a region in `failed` (and every later
/// removal that touched the same edges), newest first, so that regions
/// triangulated piece by piece keep matching their neighbours. Returns the
/// regions outside `failed` whose boundary changed.
/// `undone` (one flag per removal) carries what earlier calls put back.
std::vector<std::uint32_t> restore_vertices(Regions& regions, const std::vector<Removal>& removals,
                                            const std::vector<char>& failed, std::vector<char>& undone);

}  // namespace ember::core
