#pragma once
// The direct route of the solid path: the result's triangle mesh straight
// from the intersection curve, for two solid operands that meet in general
// position. No convex pieces, no weld, no T-junction search, no region merge.
//
// The solid path (solid_route.hpp) cuts each touched triangle into convex BSP
// pieces whose cut lines run on to the piece's boundary; the mesh stage
// (mesh_output.hpp) then welds their corners by position, inserts the points
// where those extended cuts end as T-junctions into the neighbours, merges
// the pieces of each plane back into regions and removes those points again.
// Where every pair of meeting triangles t (of one operand) and f (of the
// other) meets transversally, with no corner of either on the other's plane
// and no edge of either crossing the other's edge, all of that is known
// without geometry:
//  * t meets f in one segment (a chord of t), whose two end points are each
//    an edge of one triangle crossing the interior of the other. Such a
//    point is *named* by the edge (its two welded vertex ids) and the
//    triangle it crosses: every triangle that has the point computes the
//    same name (both triangles of the edge, and the crossed one), so equal
//    points get equal names without a sort by position, and different names
//    are different points (two names of one point would need an edge of the
//    other operand through the interior of a triangle of it, or an edge
//    crossing an edge).
//  * an edge of f that crosses t's interior is shared by exactly two
//    triangles of f's (closed, manifold) operand, both meeting t: the chords
//    join there into polylines that run from t's boundary to t's boundary,
//    and into closed curves inside t.
//  * the chords cut t into faces, walked counter-clockwise along t's
//    boundary and the polylines; a closed curve bounds a face of its own and
//    is a hole of the face around it (nesting by an exact ray-crossing
//    test). A chord of f, traversed along
//    d = n_t x n_f, has the inside of f's solid on its left; which way a
//    face walk traverses a polyline follows from the signs of the crossing
//    edges' end points (direct_faces.cpp), so every face knows its winding
//    numbers without a trace: t's own operand changes across t, f's is 1 on
//    the inside of a chord and 0 outside.
// Each kept face is ear-clipped exactly in t's plane (triangulate_loop,
// triangulate_with_holes); a point where two triangles meet is a vertex of
// every face that reaches it, so the mesh is closed by construction, with no
// vertex inside any edge.
// Untouched triangles keep the solid path's classification (one trace per
// component) and pass through as they are.
#include <atomic>
#include <optional>
#include <span>

#include "core/output/output_vertices.hpp"
#include "core/output/mesh_output.hpp"
#include "core/route/solid/solid_route.hpp"

namespace ember::core {

/// The result's mesh for two operands, both solid in `ctx`, from the
/// partners of the solid path's step 1 (find_partners). nullopt when the
/// route does not apply: more or fewer than two operands, some meeting pair
/// not in general position, closed curves whose nesting cannot be decided,
/// an edge at a crossing that is not manifold, a face that ear clipping
/// cannot take, a failed trace, or `stop` set. The caller then takes the solid
/// path's pieces and the mesh stage, which handle all of these.
/// Deterministic: the output does not depend on the schedule.
std::optional<MeshOutput> direct_solid_mesh(const GridTriangles& grid, const Box& box, const SolveContext& ctx,
                                            const OperandTrees& trees, const Partners& partners, const Quantizer& q,
                                            std::span<const Provenance> sources, const InputTopology& topology,
                                            const std::atomic<bool>& stop);

}  // namespace ember::core
