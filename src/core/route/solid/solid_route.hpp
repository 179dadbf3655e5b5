#pragma once
// The solid path: the Boolean of operands that are all solid (proven or
// promised: closed, outward, free of self-intersections, w in {0, 1}),
// without the kd subdivision.
//
// The subdivision exists to keep every leaf small and to carry a reference
// point with known winding numbers to it (paper Sections 4.1-4.2). With solid
// operands most of that work is spent far from the only places where the
// result differs from the inputs: where triangles of different operands
// meet. Fig. 11's shortcuts, carried to their end:
//  1. broad phase: one Hilbert-ordered tree per operand (triangle_tree.hpp); the pairs
//     of triangles of different operands whose boxes meet. A triangle in no
//     pair is *untouched*: no other operand's surface comes near it.
//  2. a touched triangle t is cut by its partners exactly as in a leaf
//     (pieces.hpp): lower-id coplanar partners cut away what they cover
//     (Fig. 8), transverse ones cut along their planes where the chord has
//     length (C3). No other polygon can cut t: every polygon meeting t is a
//     partner (its box meets t's), and t's own operand never crosses t.
//  3. each piece takes its winding numbers from across an input edge (an
//     untouched neighbour's component, or a neighbour's piece:
//     solid_handover.hpp), or from a piece of t across a cut line
//     (CutHandover: the cutting partner's operand changes by one where the
//     shared stretch lies in the partner), or else by a segment trace from a
//     point outside the root box (winding numbers 0) along t's dominant
//     axis onto a point strictly inside the piece (Section 3.4's tweak at
//     the end point), the other operands' triangles found through their
//     trees. t's operand is solid: 0 in front of t, 1 behind, its triangles
//     never traced.
//  4. untouched triangles of one operand joined across manifold edges
//     (GridTriangles::neighbors) share their winding numbers: near such an
//     edge only the two triangles exist (no other operand comes near, and a
//     solid operand's edge has no third triangle), so the regions in front
//     of both are one region, and those behind. One trace per component.
// Every decision is the exact predicate the leaves use; the output is the
// same point set as the subdivision's (the pieces differ: no split-plane
// cuts), so the mesh stage makes the same surfaces.
#include <atomic>
#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include "core/search/operand_trees.hpp"
#include "core/support/principal_frame.hpp"
#include "core/model/grid_triangles.hpp"
#include "core/search/triangle_tree.hpp"
#include "core/support/fill_vector.hpp"
#include "core/model/output_polygon.hpp"
#include "core/model/solve_context.hpp"

namespace ember::core {

/// The meeting pairs of triangles of different operands (step 1), both
/// ways, grouped by triangle: partners of id are ids[begin[id] ..
/// begin[id + 1]), ascending. None, with gave_up, when the search passed
/// its budget.
struct Partners {
  std::vector<std::uint32_t> begin, ids;
  bool gave_up = false;
  bool touched(std::uint32_t id) const { return begin[id + 1] > begin[id]; }
  std::span<const std::uint32_t> of(std::uint32_t id) const {
    return {ids.data() + begin[id], begin[id + 1] - begin[id]};
  }
};

/// A frame in which operands X and Y's slivers lie apart, if a sample of X's
/// triangles queried against Y's tree shows it worth its extents
/// (frame_sample.hpp): of X's principal frame and Y's, the one that
/// dismisses more. An operand of long slivers off the axes beside or inside
/// the other gets one (its sliver operand's); ordinary pairs get none, and
/// neither do pairs whose many exact tests the frames hardly thin (the
/// sample dismisses too few pairs per triangle either way round to pay for
/// the extents). None where either operand has fewer than 256 triangles.
/// Deterministic (a fixed sample). Public for its tests.
std::optional<FrameAxes> partner_frame(std::span<const std::array<IntPoint, 3>> x,
                                       std::span<const std::array<IntPoint, 3>> y, const TriangleTree& y_tree);

/// Broad and narrow phase: the meeting pairs of the n triangles (ids) of
/// `trees`' operands (their diagonals too). Deterministic (sorted), whatever
/// the schedule; incomplete (and not to be used) once `stop` is set. Gives
/// up (Partners::gave_up) once the slot pairs of the leaf pairs it visited
/// (TriangleTree::kLeaf^2 each) pass `budget`.
Partners find_partners(const GridTriangles& grid, const OperandTrees& trees, std::size_t n,
                       const std::atomic<bool>& stop, std::size_t budget = SIZE_MAX);

/// The budget of a partner search started before the proof of its premise
/// ended (boolean.cpp), per input triangle (plus kSpeculativeAllowance): the
/// search gives up, and runs again once the proof has passed. In those
/// units the budget lies well above what ordinary pairs visit per triangle
/// (even slivers off the axes without a common frame, partner_frame), and
/// far below a pile of slivers whose proof then fails: without the budget
/// such a search would hold a thread for the whole of the proof it waits
/// on.
inline constexpr std::size_t kSpeculativePartnersPerTriangle = 512;
inline constexpr std::size_t kSpeculativeAllowance = std::size_t{1} << 16;

/// The Boolean of the grid triangles (triangle i has corners
/// grid.corners[i]; every operand solid in `ctx`; `trees` its operands'
/// triangle trees, build_operand_trees over the operands' ranges of ids)
/// inside the root box `box`, whose boundary no triangle touches. Reads no
/// root soup (root_problem.hpp). The pieces on the result's surface, in a
/// deterministic order (unbuilt whole triangles and explicit pieces; no
/// paths). nullopt if some piece found no non-degenerate trace (the caller
/// then solves on the subdivision instead), or if `abandon` was set: a run
/// started before the proof of its premise ended stops early once the proof
/// fails (boolean.cpp), checking the flag between steps and within them.
/// `partners`, if given, are step 1's, already found (find_partners).
std::optional<std::vector<OutputPolygon>> solve_solid(const GridTriangles& grid, const Box& box,
                                                      const SolveContext& ctx, const OperandTrees& trees,
                                                      const std::atomic<bool>* abandon = nullptr,
                                                      const Partners* partners = nullptr);

/// An untouched triangle on the result's surface: its id, and whether it
/// is emitted reversed.
struct KeptTriangle {
  std::uint32_t id;
  bool flip;
};

/// Steps 2 and 4 alone, for the direct route (direct_mesh.hpp), which cuts
/// the touched triangles itself: the untouched triangles on the result's
/// surface, by id, classified by one trace per component. nullopt if a
/// trace failed or `stop` was set.
std::optional<FillVector<KeptTriangle>> solid_untouched(const GridTriangles& grid, const Box& box,
                                                        const SolveContext& ctx, const OperandTrees& trees,
                                                        const Partners& partners, const std::atomic<bool>& stop);

}  // namespace ember::core
