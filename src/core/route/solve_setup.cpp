// The set-up shared by the proof and the routes (solve_setup.hpp).
#include "core/route/solve_setup.hpp"

namespace ember::core {

namespace {

/// The root box pads the grid's bounds by one step, so the reference point
/// (lo + 1/2 on every axis) lies off all geometry, outside every operand.
Subproblem root_shell(const PreparedInput& input, std::size_t operands) {
  Subproblem shell;
  for (int a = 0; a < 3; ++a) {
    shell.box.lo[a] = input.lo[a] - 1;
    shell.box.hi[a] = input.hi[a] + 1;
    shell.ref.num[a] = 2 * shell.box.lo[a] + 1;
  }
  shell.ref.shift = 1;
  shell.ref_w.assign(operands, 0);
  return shell;
}

}  // namespace

std::unique_ptr<SolveSetup> set_up_solve(PreparedInput& input, const BooleanRule& rule, const BooleanOptions& options) {
  const std::size_t operands = input.open_edges.size();
  auto s = std::make_unique<SolveSetup>();
  s->input = &input;
  if (rule.expression) {
    s->expression = *rule.expression;
    s->indicator = [&e = *s->expression](WindingVector w) { return e.inside(w); };
  } else if (rule.layers) {
    s->indicator = indicator_for(Operation::Union, operands);  // the crossing counts instead (ctx.layers)
  } else {
    s->indicator = options.indicator ? options.indicator : indicator_for(rule.op, operands, options.min_k);
  }
  // Its soup is built where the general path or a proof's scan needs it.
  s->root =
      std::make_unique<RootProblem>(root_shell(input, operands), input.triangles.grid, input.triangles.operand_begin);
  SolveContext& ctx = s->ctx;
  ctx.operands = operands;
  ctx.inside = [&indicator = s->indicator](const Wnv& w) { return indicator(WindingVector(w.data(), w.size())); };
  ctx.layers = rule.layers;
  if (rule.expression) {
    ctx.expression = &*s->expression;
  } else if (!options.indicator && !rule.layers) {
    ctx.op = rule.op;
    ctx.min_k = options.min_k;
  }
  ctx.solid.assign(operands, options.all_solid ? 1 : 0);
  for (std::size_t i = 0; i < options.solid.size(); ++i) ctx.solid[i] |= options.solid[i] ? 1 : 0;
  ctx.closed.resize(operands);
  for (std::size_t o = 0; o < operands; ++o) ctx.closed[o] = input.open_edges[o] == 0 || ctx.solid[o];
  bool may_all_be_solid = options.route == BooleanOptions::Route::Automatic;
  for (std::size_t o = 0; o < operands; ++o)
    may_all_be_solid &= ctx.solid[o] || (options.detect_solid && input.open_edges[o] == 0);
  if (may_all_be_solid) s->trees = build_operand_trees(input.triangles.operand_begin, input.triangles.grid.corners);
  if (input.topology) input.topology->by_triangle = input.triangles.grid.vertex_ids;
  // The direct route makes one mesh; layer mode needs the pieces of all.
  s->direct_allowed =
      input.topology && operands == 2 && options.output == BooleanOptions::Output::Triangles && !rule.layers;
  return s;
}

}  // namespace ember::core
