#pragma once
// What the proof and the routes share (boolean.cpp): the root problem, the
// solve context (indicator, closed and solid operands) and, when every
// operand can end up solid, the operands' triangle trees.
#include <atomic>
#include <memory>
#include <optional>

#include "core/input/prepare.hpp"
#include "core/model/solve_context.hpp"
#include "core/route/general/root_problem.hpp"
#include "core/search/operand_trees.hpp"
#include "ember/boolean.hpp"

namespace ember::core {

struct SolveSetup {
  PreparedInput* input = nullptr;
  Indicator indicator;            ///< ctx.inside calls it
  std::optional<Csg> expression;  ///< ctx.expression points here
  std::unique_ptr<RootProblem> root;
  SolveContext ctx;
  /// Built only when every operand can end up solid (promised, or closed and
  /// to be proven): the proof searches each against itself, the solid path
  /// pairs of them. Otherwise the proof builds its own.
  std::optional<OperandTrees> trees;
  /// The direct route may run: two operands, triangle output, ids numbered.
  bool direct_allowed = false;
  /// The leaves' diagonal extents serve the two broad phases only (the
  /// proof's contact searches, the partner search): freed when the last of
  /// them ends, before the direct route's peak (32 bytes per input triangle).
  std::atomic<int> broad_phases{1};  ///< the partner search; the proof adds itself
  void broad_phase_done() {
    if (broad_phases.fetch_sub(1) != 1) return;
    trees->diagonals = {};
  }
};

/// What the Boolean computes: `op` (with BooleanOptions::min_k or
/// ::indicator), `expression` when it is set, or every layer in layer mode.
struct BooleanRule {
  Operation op = Operation::Union;
  const Csg* expression = nullptr;
  bool layers = false;
};

/// The set-up of the solve over `input`'s grid triangles (which must have
/// some) for `rule`. Builds the trees inside the caller's task arena.
std::unique_ptr<SolveSetup> set_up_solve(PreparedInput& input, const BooleanRule& rule,
                                         const BooleanOptions& options);

}  // namespace ember::core
