#pragma once
// Input triangles that the subdivision cut into pieces but that reach the
// output whole, put back together before the mesh stage.
#include <span>
#include <vector>

#include "core/model/output_polygon.hpp"
#include "core/route/general/subproblem.hpp"

namespace ember::core {

/// When every piece that the subdivision cut from a triangle reached the
/// output uncut by its leaf (OutputPolygon::whole_piece) and with one
/// orientation, the pieces together are exactly the triangle: their shares
/// 2^-splits sum to 1 only if none is missing. The triangle (unbuilt, pointing
/// at its grid corners `corners[id]`, as the soup held it) replaces its first piece
/// and the other pieces are removed, so the mesh stage has no cut points to
/// weld, merge and remove for it. Order is otherwise kept.
/// Returns how many triangles were put back together.
std::size_t merge_whole_triangles(std::vector<OutputPolygon>& polys);

/// Gives every path piece left after merge_whole_triangles its vertices:
/// its triangle clipped by the splits of paths[p.path] in their order,
/// keeping the side the path took, which is exactly the polygon the
/// subdivision made (split_range clips the same way; a split that does not
/// cut the piece leaves it as it is).
void expand_path_pieces(std::vector<OutputPolygon>& polys, std::span<const SplitPath> paths);

}  // namespace ember::core
