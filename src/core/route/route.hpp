#pragma once
// Stage 3 of the Boolean (boolean.cpp): the route that solves it.
//  * solid path (route/solid): every operand solid; no subdivision, only
//    triangles that another operand's come near are cut and traced;
//  * direct route (route/direct): the solid path for two operands meeting
//    in general position, making the triangle mesh itself;
//  * general path (route/general): the paper's kd subdivision, exact for any
//    input, and where the solid path declines.
#include <atomic>
#include <optional>
#include <vector>

#include "core/model/output_polygon.hpp"
#include "core/output/mesh_output.hpp"
#include "core/route/solve_setup.hpp"

namespace ember::core {

/// What the solid path made: the result's mesh (the direct route), or its
/// pieces for the mesh stage; neither if it declined or was abandoned.
/// `gave_up`: a speculative run's partner search passed its budget (it runs
/// again once the proof has passed).
struct SolidRoute {
  std::optional<MeshOutput> mesh;
  std::optional<std::vector<OutputPolygon>> polys;
  bool gave_up = false;
};

/// The solid path under `ctx` (every operand solid in it). `abandon`, if
/// given, makes it a speculative run, started before the proof of its
/// premise ended: it stops once the flag is set, and its partner search has
/// a budget (where the operands' triangles crowd each other by the hundreds,
/// the search would hold a thread for the whole proof, which then usually
/// fails; past the budget it gives up and, if the proof passes, runs again).
SolidRoute run_solid_route(SolveSetup& setup, const SolveContext& ctx, const std::atomic<bool>* abandon);

/// The route's result: a finished mesh (direct route) or output pieces.
struct RouteResult {
  std::vector<OutputPolygon> polys;
  std::optional<MeshOutput> mesh;
  bool solid_path = false;           ///< the solid path solved it
  bool direct_mesh = false;          ///< the direct route made the mesh
  std::size_t merged_triangles = 0;  ///< general path: input triangles put back together whole
};

/// Solves with the solid path when every operand is solid (reusing
/// `speculative` when it ran to the end), else, or where the solid path
/// declines, with the general path. Run it inside the Boolean's task arena.
RouteResult run_route(SolveSetup& setup, std::optional<SolidRoute> speculative);

}  // namespace ember::core
