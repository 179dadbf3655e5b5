// Stage 3 of the Boolean (route.hpp).
#include "core/route/route.hpp"

#include <algorithm>
#include <cstdint>

#include "core/route/direct/direct_mesh.hpp"
#include "core/route/general/subdivide.hpp"
#include "core/route/general/whole_triangles.hpp"
#include "core/route/solid/solid_route.hpp"

namespace ember::core {

SolidRoute run_solid_route(SolveSetup& setup, const SolveContext& ctx, const std::atomic<bool>* abandon) {
  SolidRoute route;
  const std::atomic<bool> never{false};
  const std::atomic<bool>& stop = abandon ? *abandon : never;
  const PreparedInput& in = *setup.input;
  const GridTriangles& grid = in.triangles.grid;
  const std::size_t n = grid.corners.size();
  const std::size_t budget = abandon ? kSpeculativePartnersPerTriangle * n + kSpeculativeAllowance : SIZE_MAX;
  const Partners partners = find_partners(grid, *setup.trees, n, stop, budget);
  if (partners.gave_up) {
    route.gave_up = true;
    return route;
  }
  setup.broad_phase_done();
  if (stop.load()) return route;
  if (setup.direct_allowed)
    route.mesh = direct_solid_mesh(grid, setup.root->box(), ctx, *setup.trees, partners, in.quantizer,
                                   in.triangles.sources, *in.topology, stop);
  if (!route.mesh && !stop.load())
    route.polys = solve_solid(grid, setup.root->box(), ctx, *setup.trees, abandon, &partners);
  return route;
}

RouteResult run_route(SolveSetup& setup, std::optional<SolidRoute> speculative) {
  RouteResult result;
  // All operands solid: the solid path needs no subdivision. It declines
  // only where every trace it tried met something degenerately; the
  // subdivision then solves as always.
  const bool all_solid = std::all_of(setup.ctx.solid.begin(), setup.ctx.solid.end(), [](char s) { return s != 0; });
  if (!all_solid) setup.trees.reset();  // the subdivision does not use them
  if (setup.trees) {
    SolidRoute route =
        speculative && !speculative->gave_up ? std::move(*speculative) : run_solid_route(setup, setup.ctx, nullptr);
    result.solid_path = route.mesh || route.polys;
    if (route.mesh) {
      result.mesh = std::move(route.mesh);
      result.direct_mesh = true;
      return result;
    }
    if (route.polys) {
      result.polys = std::move(*route.polys);
      return result;
    }
  }
  SolveOutput solved = solve(setup.root->take(), setup.ctx);
  result.polys = std::move(solved.polys);
  result.merged_triangles = merge_whole_triangles(result.polys);
  expand_path_pieces(result.polys, solved.paths);
  return result;
}

}  // namespace ember::core
