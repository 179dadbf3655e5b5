#pragma once
// The recursive EMBER solver: adaptive subdivision with reference-point
// propagation (Section 4.2) down to leaves (leaf.hpp).
#include <cstddef>
#include <vector>

#include "core/model/output_polygon.hpp"
#include "core/model/solve_context.hpp"
#include "core/route/general/subproblem.hpp"

namespace ember::core {

/// Early termination (Section 4.5.2): true when every winding-number vector
/// reachable inside the subproblem maps to the same side of the indicator,
/// so it cannot contribute output. Operands without polygons in the
/// subproblem keep the reference point's winding number.
bool indicator_constant(const Subproblem& problem, const SolveContext& ctx);

/// Whether splitting `polygons` polygons, `straddling` of which land in both
/// children, is worth it, or the subproblem is a pile better solved as one
/// leaf (subdivide.cpp). A pile leaf's work grows about as the square of its
/// size (each polygon meets every polygon whose box meets its own), so the
/// split pays only while two children of (n + s) / 2 polygons cost less than
/// one leaf of n: (n + s)^2 < 2 n^2, that is s < (sqrt 2 - 1) n ~ 0.41 n.
/// (With 3/4 of the polygons allowed to straddle, a pile's leaves would hold
/// each of its triangles many times over.)
bool split_pays(std::size_t polygons, std::size_t straddling);

/// What solve() emits: output polygons in a deterministic order that does not
/// depend on scheduling, and the paths their path pieces refer to.
struct SolveOutput {
  std::vector<OutputPolygon> polys;
  std::vector<SplitPath> paths;
};

/// Solves a subproblem.
SolveOutput solve(Subproblem&& problem, const SolveContext& ctx);

/// The output form of soup polygon p, a whole subdivision piece: unbuilt if no
/// split cut its triangle, else by path (path 0: the emitting subproblem's,
/// which solve() numbers).
OutputPolygon whole_piece_output(const SoupPolygon& p, const Crossing& crossing);

}  // namespace ember::core
