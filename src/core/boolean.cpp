// The public Boolean as a sequence of named stages:
//
//   prepare_input  (input/prepare.hpp)   meshes -> grid triangles, closedness
//   set_up_solve   (route/solve_setup.hpp) root problem, indicator, triangle trees
//   prove_solid    (proof/prove.hpp)     exact proof that operands are solid
//   run_route      (route/route.hpp)     solid path, direct route or general path
//   build_output   (output/build_output.hpp) watertight triangle mesh or raw polygons
//
// At more than one thread the solid path starts alongside the proof, on the
// premise the proof is about to establish (docs/design.md, "Pipeline"): a
// small input's proof and solve are chains of short loops and serial steps
// that leave the second thread idle, so two independent tasks keep the
// threads busier than either alone. Same inputs as after the proof, so the
// same result; a failed proof abandons the run and the general path solves.
#include "ember/boolean.hpp"

#include <tbb/info.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <chrono>
#include <optional>
#include <string>

#include "core/input/face_groups.hpp"
#include "core/input/prepare.hpp"
#include "core/output/build_output.hpp"
#include "core/output/properties.hpp"
#include "core/proof/prove.hpp"
#include "core/route/route.hpp"
#include "core/route/solve_setup.hpp"
#include "ember/csg.hpp"
#include "ember/error.hpp"

namespace ember {

namespace {

using Clock = std::chrono::steady_clock;

double ms_between(Clock::time_point a, Clock::time_point b) {
  return std::chrono::duration<double, std::milli>(b - a).count();
}

/// The progress hook, if any. Calls happen only between the parallel phases,
/// on the calling thread, so the callback never runs concurrently with itself.
/// The fractions are a fixed guess at each phase's share of a typical run.
void report(const BooleanOptions& options, std::string_view phase, double fraction) {
  if (options.progress) options.progress(phase, fraction);
}

void check_options(std::span<const Mesh> operands, const BooleanOptions& options) {
  if (operands.empty()) throw Error("boolean: no operands given; pass at least one mesh");
  if (options.threads < 0) throw Error("boolean: threads must be >= 0 (0 = all hardware threads)");
  if (!options.solid.empty() && options.solid.size() != operands.size())
    throw Error("boolean: options.solid must be empty or have one entry per operand (" +
                std::to_string(operands.size()) + "), got " + std::to_string(options.solid.size()));
}

/// More threads than the machine has only oversubscribe it (and make TBB
/// warn on stderr): clamped. Results do not depend on the count.
int thread_count(const BooleanOptions& options) {
  const int hardware = tbb::info::default_concurrency();
  return options.threads > 0 ? std::min(options.threads, hardware) : hardware;
}

void record_input(core::PreparedInput& in, BooleanResult& result) {
  BooleanStats& s = result.stats;
  s.grid_step = in.quantizer.grid_spacing();
  s.operands = std::move(in.reports);
  result.warnings = std::move(in.warnings);
  for (const OperandReport& r : s.operands) {
    s.collapsed_triangles += r.collapsed_triangles;
    s.flipped_triangles += r.flipped_triangles;
  }
  s.input_triangles = in.input_triangles;
  s.dropped_degenerate = in.triangles.dropped_degenerate;
}

/// The times of the phases (BooleanStats::diagnostics).
struct PhaseTimes {
  double setup_ms = 0, proof_ms = 0, solve_ms = 0, output_ms = 0;
};

/// The diagnostics, in the order the CLI's --stats prints them.
std::vector<Diagnostic> diagnostics_of(const core::RouteResult& route, const core::MeshOutputStats& m,
                                       const PhaseTimes& t) {
  const auto count = [](std::size_t n) { return static_cast<double>(n); };
  return {{"merged_triangles", count(route.merged_triangles)},
          {"solid_path", route.solid_path ? 1.0 : 0.0},
          {"direct_mesh", route.direct_mesh ? 1.0 : 0.0},
          {"tjunctions_resolved", count(m.tjunctions)},
          {"collinear_removed", count(m.collinear_removed)},
          {"regions", count(m.regions)},
          {"fallback_regions", count(m.fallback_regions)},
          {"setup_ms", t.setup_ms},
          {"proof_ms", t.proof_ms},
          {"solve_ms", t.solve_ms},
          {"output_ms", t.output_ms},
          {"weld_ms", m.weld_ms},
          {"tjunction_ms", m.tjunction_ms},
          {"regions_ms", m.regions_ms},
          {"triangulate_ms", m.triangulate_ms}};
}

void record_output(core::BuiltOutput&& out, BooleanResult& result) {
  BooleanStats& s = result.stats;
  s.dropped_slivers = out.dropped_slivers;
  const core::MeshOutputStats& m = out.stats;
  s.rounded_degenerate = m.rounded_degenerate;
  if (m.fallback_regions)
    result.warnings.push_back(std::to_string(m.fallback_regions) +
                              " planar regions could not be merged and were triangulated piece by piece; the mesh "
                              "may have T-junctions there");
  if (m.rounded_degenerate)
    result.warnings.push_back(std::to_string(m.rounded_degenerate) +
                              " output triangles have zero area after rounding to double (exact result is fine)");
  result.mesh = std::move(out.mesh);
  result.provenance = std::move(out.provenance);
  s.output_polygons = result.mesh.face_count();
  s.output_vertices = result.mesh.vertices.size();
}

/// Stages 2 to 4 on a non-empty input: the solve's set-up, the proof (with
/// the solid path beside it where it can run), the route. Fills the proof's
/// part of the result and its time.
core::RouteResult solve(core::PreparedInput& in, const core::BooleanRule& rule, const BooleanOptions& options,
                        int threads, tbb::task_arena& arena, BooleanResult& result, Clock::time_point& proved) {
  std::unique_ptr<core::SolveSetup> setup;
  arena.execute([&] { setup = core::set_up_solve(in, rule, options); });
  for (std::size_t o = 0; o < setup->ctx.solid.size(); ++o)
    if (setup->ctx.solid[o]) result.stats.operands[o].solid = SolidStatus::Promised;
  std::optional<core::SolidRoute> speculative;
  bool speculated = false;
  if (options.detect_solid && core::has_operands_to_prove(*setup)) {
    report(options, "solid check", 0.1);
    core::SolveContext premise = setup->ctx;
    premise.solid.assign(premise.solid.size(), 1);
    const auto alongside = [&](const std::atomic<bool>& disproved) {
      speculative = core::run_solid_route(*setup, premise, &disproved);
    };
    core::SolidProof proof;
    arena.execute([&] { proof = core::prove_solid(*setup, threads, alongside); });
    core::record_proof(proof, *setup, result.stats.operands, result.warnings);
    speculated = proof.speculated;
    if (speculated) proved = proof.done;
  }
  for (const char s : setup->ctx.solid) result.stats.solid_operands += s != 0;
  if (in.topology) in.topology->solid = setup->ctx.solid;
  if (!speculated) proved = Clock::now();
  report(options, "solve", 0.2);
  core::RouteResult route;
  arena.execute([&] { route = core::run_route(*setup, std::move(speculative)); });
  return route;
}

/// The expression's own preconditions (ember/csg.hpp): it uses exactly the
/// operands given, and no option that would replace or parameterize it.
void check_expression(std::span<const Mesh> operands, const Csg& expression, const BooleanOptions& options) {
  if (expression.nodes().empty()) throw Error("boolean: the expression is empty (a default-constructed Csg)");
  if (options.indicator) throw Error("boolean: options.indicator cannot be combined with an expression");
  if (options.min_k != 1)
    throw Error("boolean: options.min_k does not apply to an expression; use Csg::at_least(k, terms)");
  if (expression.operand_count() > operands.size())
    throw Error("boolean: the expression uses operand " + std::to_string(expression.operand_count() - 1) +
                " but only " + std::to_string(operands.size()) + " operands were given");
  for (std::size_t i = 0; i < operands.size(); ++i)
    if (!expression.uses(i))
      throw Error(
          "the expression does not use this operand; pass only the operands it names (each shapes the "
          "common grid)",
          {.operand = i});
}

/// The preconditions of layer mode (boolean_layers).
void check_layers(std::span<const Mesh> operands, const BooleanOptions& options) {
  if (options.indicator) throw Error("boolean_layers: options.indicator does not apply (the layers are fixed)");
  if (options.min_k != 1) throw Error("boolean_layers: options.min_k does not apply (every k is computed)");
  if (operands.size() > core::OutputPolygon::kMaxLayers)
    throw Error("boolean_layers: at most " + std::to_string(core::OutputPolygon::kMaxLayers) + " operands, got " +
                std::to_string(operands.size()));
}

/// The pieces of layer k (1-based) among a layer-mode route's.
core::RouteResult layer_of(const core::RouteResult& all, std::size_t k) {
  core::RouteResult layer;
  layer.solid_path = all.solid_path;
  layer.merged_triangles = all.merged_triangles;
  for (const core::OutputPolygon& p : all.polys)
    if (p.layer_lo < k && k <= p.layer_hi) layer.polys.push_back(p);
  return layer;
}

/// The Boolean of `rule`; in layer mode one result per layer, else one.
std::vector<BooleanResult> run_boolean(std::span<const Mesh> operands, const core::BooleanRule& rule,
                                       const BooleanOptions& options) {
  const auto start = Clock::now();
  report(options, "prepare", 0.0);
  check_options(operands, options);
  if (rule.expression)
    check_expression(operands, *rule.expression, options);
  else if (rule.layers)
    check_layers(operands, options);
  else if (!options.indicator)
    indicator_for(rule.op, operands.size(), options.min_k);  // checks min_k
  const core::FaceGroups groups = core::FaceGroups::of(operands);
  const core::PropertyPlan properties = core::PropertyPlan::of(operands);
  BooleanResult result;
  const int threads = thread_count(options);
  result.stats.threads = threads;
  tbb::task_arena arena(threads);

  core::PreparedInput in;
  arena.execute([&] { in = core::prepare_input(operands, options.allow_open); });
  record_input(in, result);
  // With properties no region spans two input faces (each interpolates its own).
  const std::vector<std::uint32_t> source_groups =
      groups.region_keys(operands, in.triangles.sources, /*per_face=*/!properties.empty());
  const auto setup_done = Clock::now();
  PhaseTimes times;
  times.setup_ms = ms_between(start, setup_done);

  Clock::time_point proved = setup_done;
  core::RouteResult route;
  if (!in.triangles.grid.corners.empty()) route = solve(in, rule, options, threads, arena, result, proved);
  times.proof_ms = ms_between(setup_done, proved);
  const auto solved = Clock::now();
  times.solve_ms = ms_between(proved, solved);

  report(options, "export", 0.9);
  std::vector<BooleanResult> results;
  const std::size_t count = rule.layers ? operands.size() : 1;
  std::vector<core::MeshOutputStats> mesh_stats;
  for (std::size_t k = 1; k <= count; ++k) {
    core::BuiltOutput out;
    core::RouteResult piece = rule.layers ? layer_of(route, k) : std::move(route);
    arena.execute([&] { out = core::build_output(std::move(piece), in, options.output, source_groups); });
    mesh_stats.push_back(out.stats);
    results.push_back(k < count ? result : std::move(result));
    record_output(std::move(out), results.back());
    groups.assign(results.back().provenance, results.back().mesh);
    if (!properties.empty())
      for (std::string& w :
           core::interpolate_properties(properties, operands, results.back().provenance, results.back().mesh))
        results.back().warnings.push_back(std::move(w));
  }
  const auto end = Clock::now();
  times.output_ms = ms_between(solved, end);
  for (std::size_t k = 0; k < results.size(); ++k) {
    results[k].stats.time_ms = ms_between(start, end);
    results[k].stats.diagnostics = diagnostics_of(route, mesh_stats[k], times);
  }
  report(options, "done", 1.0);
  return results;
}

}  // namespace

BooleanResult boolean(std::span<const Mesh> operands, Operation op, const BooleanOptions& options) {
  return std::move(run_boolean(operands, {.op = op}, options).front());
}

BooleanResult boolean(std::span<const Mesh> operands, const Csg& expression, const BooleanOptions& options) {
  return std::move(run_boolean(operands, {.expression = &expression}, options).front());
}

std::vector<BooleanResult> boolean_layers(std::span<const Mesh> operands, const BooleanOptions& options) {
  return run_boolean(operands, {.layers = true}, options);
}

}  // namespace ember
