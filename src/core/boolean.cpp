// The public Boolean: validation, quantization onto the integer grid, the
// exact core, and export back to the caller's units.
#include "ember/boolean.hpp"

#include <tbb/info.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_invoke.h>
#include <tbb/task_arena.h>
#include <tbb/task_group.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstring>
#include <optional>
#include <string>
#include <unordered_map>

#include "core/route/direct/direct_mesh.hpp"
#include "core/input/grid_input.hpp"
#include "core/input/input_triangles.hpp"
#include "core/route/general/root_problem.hpp"
#include "core/model/indicator.hpp"
#include "core/output/mesh_output.hpp"
#include "core/route/general/solve.hpp"
#include "core/proof/solid_proof.hpp"
#include "core/route/solid/solid_route.hpp"
#include "core/route/general/whole_triangles.hpp"
#include "core/input/quantize.hpp"
#include "ember/error.hpp"

namespace ember {

namespace {

/// What the solid path made: the result's mesh (the direct route), or its
/// pieces for the mesh stage; neither if it declined or was abandoned.
/// `gave_up`: a speculative run's partner search passed its budget (it runs
/// again once the proof has passed).
struct SolidRoute {
  std::optional<core::MeshOutput> mesh;
  std::optional<std::vector<core::OutputPolygon>> polys;
  bool gave_up = false;
};

double ms_between(std::chrono::steady_clock::time_point a, std::chrono::steady_clock::time_point b) {
  return std::chrono::duration<double, std::milli>(b - a).count();
}

std::string operand_name(std::size_t i) { return "operand " + std::to_string(i); }

Mesh export_mesh(const std::vector<core::OutputPolygon>& polys, const Quantizer& q, std::span<const Provenance> sources,
                 std::vector<Provenance>& provenance, std::size_t& dropped) {
  struct Key {
    std::uint64_t v[3];
    bool operator==(const Key& o) const { return std::memcmp(v, o.v, sizeof v) == 0; }
  };
  struct KeyHash {
    std::size_t operator()(const Key& k) const { return (k.v[0] * 0x9e3779b97f4a7c15ULL) ^ (k.v[1] * 31) ^ k.v[2]; }
  };
  // Round every vertex in parallel (the costly part), then weld serially in
  // output order so vertex numbering is deterministic.
  std::vector<std::size_t> offset(polys.size() + 1, 0);
  for (std::size_t i = 0; i < polys.size(); ++i) offset[i + 1] = offset[i] + core::corner_count(polys[i]);
  std::vector<Vec3d> rounded(offset.back());
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, polys.size(), 256), [&](const tbb::blocked_range<std::size_t>& r) {
    for (std::size_t i = r.begin(); i != r.end(); ++i) {
      const core::OutputPolygon& p = polys[i];
      const std::size_t n = core::corner_count(p);
      for (std::size_t k = 0; k < n; ++k) {
        const std::size_t at = p.flip ? n - 1 - k : k;
        const Vec3d x = core::unbuilt(p) ? q.dequantize((*p.corners)[at]) : q.dequantize(p.vertices[at]);
        rounded[offset[i] + k] = {x.x + 0.0, x.y + 0.0, x.z + 0.0};  // -0.0 -> +0.0 so equal points weld
      }
    }
  });
  Mesh mesh;
  std::unordered_map<Key, std::uint32_t, KeyHash> ids;
  ids.reserve(rounded.size() / 2);
  std::vector<std::uint32_t> face;
  for (std::size_t i = 0; i < polys.size(); ++i) {
    const core::OutputPolygon& p = polys[i];
    face.clear();
    for (std::size_t k = offset[i]; k < offset[i + 1]; ++k) {
      const Vec3d& x = rounded[k];
      Key key{};
      std::memcpy(&key.v[0], &x.x, 8);
      std::memcpy(&key.v[1], &x.y, 8);
      std::memcpy(&key.v[2], &x.z, 8);
      auto [it, fresh] = ids.try_emplace(key, static_cast<std::uint32_t>(mesh.vertices.size()));
      if (fresh) mesh.vertices.push_back(x);
      // Distinct exact points may round to the same double: drop repeats.
      if (face.empty() || face.back() != it->second) face.push_back(it->second);
    }
    while (face.size() > 1 && face.front() == face.back()) face.pop_back();
    // An exact sliver can round to collinear doubles; such a face has no area
    // in the caller's units and is dropped rather than emitted degenerate.
    if (face.size() < 3 || core::rounded_area_is_zero(mesh.vertices, face)) {
      ++dropped;
      continue;
    }
    mesh.add_face(face);
    provenance.push_back(sources[p.id]);
  }
  return mesh;
}

/// The progress hook, if any. Calls happen only between the parallel phases,
/// on the calling thread, so the callback never runs concurrently with itself.
/// The fractions are a fixed guess at each phase's share of a typical run.
void report(const BooleanOptions& options, std::string_view phase, double fraction) {
  if (options.progress) options.progress(phase, fraction);
}

/// Records the solid proof's finding for operand o in the result's report
/// and, when it failed, warns why (it changes path and time).
bool record_proof(const core::SolidFinding& f, std::size_t o, BooleanResult& result) {
  OperandReport& report = result.stats.operands[o];
  report.self_intersecting_pairs = f.self_intersecting_pairs;
  report.self_intersecting_pairs_complete = f.pairs_complete;
  report.misoriented_components = f.misoriented_components;
  switch (f.verdict) {
    case core::SolidVerdict::Solid: report.solid = SolidStatus::Proven; return true;
    case core::SolidVerdict::SelfIntersecting: report.solid = SolidStatus::SelfIntersecting; break;
    case core::SolidVerdict::WrongWinding: report.solid = SolidStatus::Misoriented; break;
    case core::SolidVerdict::TooComplex:
    case core::SolidVerdict::Unclassified: report.solid = SolidStatus::Undecided; break;
  }
  result.warnings.push_back(operand_name(o) + ": " + describe_solid_check(report) +
                            "; it takes the general path, which is exact but slower "
                            "(CLI: --no-solid-check skips the check)");
  return false;
}

}  // namespace

BooleanResult boolean(std::span<const Mesh> operands, Operation op, const BooleanOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  report(options, "prepare", 0.0);
  if (operands.empty()) throw Error("boolean: no operands given; pass at least one mesh");
  if (options.threads < 0) throw Error("boolean: threads must be >= 0 (0 = all hardware threads)");
  if (!options.solid.empty() && options.solid.size() != operands.size())
    throw Error("boolean: options.solid must be empty or have one entry per operand (" +
                std::to_string(operands.size()) + "), got " + std::to_string(options.solid.size()));
  const Indicator indicator = options.indicator ? options.indicator : indicator_for(op, operands.size(), options.min_k);

  BooleanResult result;
  // More threads than the machine has only oversubscribe it (and make TBB
  // warn on stderr): clamp. Results do not depend on the count.
  const int hardware = tbb::info::default_concurrency();
  const int threads = options.threads > 0 ? std::min(options.threads, hardware) : hardware;
  result.stats.threads = threads;
  tbb::task_arena arena(threads);

  // Every step of the set-up is parallel and its result independent of the
  // split: validation, one quantization map for all operands (fitted to the
  // vertices faces use), grid triangles with welded vertex ids, the audit of
  // the rounding, closedness, and the grid triangles by id.
  core::GridInput gi;
  core::InputTriangles in;
  core::EdgeMatching edges;
  Quantizer q;
  arena.execute([&] {
    core::validate_operands(operands);
    const core::UsedVertices used = core::used_vertices(operands);
    q = core::fit_used_vertices(operands, used);
    gi = core::to_grid(operands, q, used);
    result.stats.grid_step = q.grid_spacing();
    result.stats.operands.resize(operands.size());
    // Independent: side by side for small inputs (core::side_by_side; an
    // exception from the audit reaches the caller either way).
    const auto audit = [&] { core::audit_quantization(operands, gi, q, result.stats.operands, result.warnings); };
    const auto match = [&] { edges = core::match_edges(gi); };
    if (core::side_by_side(gi)) {
      tbb::parallel_invoke(audit, match);
    } else {
      audit();
      match();
    }
    in = core::build_grid_triangles(gi, edges);
  });
  for (const OperandReport& r : result.stats.operands) {
    result.stats.collapsed_triangles += r.collapsed_triangles;
    result.stats.flipped_triangles += r.flipped_triangles;
  }
  result.stats.input_triangles = gi.triangles.size();
  result.stats.dropped_degenerate = in.dropped_degenerate;
  const std::array<std::int64_t, 3> lo = gi.lo, hi = gi.hi;
  // The mesh stage welds unbuilt triangles' corners through these ids; with
  // the manifold edges and the solid flags it narrows the T-junction search
  // (InputTopology, mesh_output.hpp).
  std::optional<core::InputTopology> topology = core::InputTopology{};
  topology->operand_base.push_back(0);
  for (const std::size_t count : gi.vertex_count) {
    if (count > UINT32_MAX - 1 - topology->operand_base.back()) {
      topology.reset();  // too many to number in 32 bits: the weld sorts every corner
      break;
    }
    topology->operand_base.push_back(topology->operand_base.back() + static_cast<std::uint32_t>(count));
  }
  gi = {};
  edges.manifold = {};
  edges.partner = {};
  const std::vector<std::size_t>& open = edges.open;
  for (std::size_t o = 0; o < operands.size(); ++o) {
    result.stats.operands[o].open_edges = open[o];
    if (open[o] == 0) continue;
    result.stats.operands[o].solid = SolidStatus::Open;
    const std::string msg = operand_name(o) + ": not closed: " + std::to_string(open[o]) +
                            " edges are not matched by an opposite edge, so inside/outside is undefined";
    if (!options.allow_open) throw Error(msg + "; repair the mesh or allow open inputs (CLI: --allow-open)");
    result.warnings.push_back(msg + "; proceeding as requested, the result may have holes");
  }
  core::GridTriangles& grid = in.grid;
  const std::span<const Provenance> sources = in.sources;

  std::vector<core::OutputPolygon> polys;
  std::optional<core::MeshOutput> direct_mesh;  // the solid path's direct route, when it applies
  const auto setup_done = std::chrono::steady_clock::now();
  result.stats.setup_ms = ms_between(start, setup_done);
  auto proved = setup_done;
  if (!grid.corners.empty()) {
    core::Subproblem shell;
    for (int a = 0; a < 3; ++a) {
      shell.box.lo[a] = lo[a] - 1;  // padding keeps the reference point off all geometry
      shell.box.hi[a] = hi[a] + 1;
      shell.ref.num[a] = 2 * shell.box.lo[a] + 1;  // lo + 1/2: inside the box, outside everything
    }
    shell.ref.shift = 1;
    shell.ref_w.assign(operands.size(), 0);
    // Its soup is built where the general path or a proof's scan needs it.
    core::RootProblem root(std::move(shell), grid, in.operand_begin);
    core::SolveContext ctx;
    ctx.operands = operands.size();
    ctx.inside = [&indicator](const core::Wnv& w) { return indicator(WindingVector(w.data(), w.size())); };
    if (!options.indicator) {
      ctx.op = op;
      ctx.min_k = options.min_k;
    }
    ctx.solid.assign(operands.size(), options.all_solid ? 1 : 0);
    for (std::size_t i = 0; i < options.solid.size(); ++i) ctx.solid[i] |= options.solid[i] ? 1 : 0;
    for (std::size_t o = 0; o < operands.size(); ++o)
      if (ctx.solid[o]) result.stats.operands[o].solid = SolidStatus::Promised;
    ctx.closed.resize(operands.size());
    for (std::size_t o = 0; o < operands.size(); ++o) ctx.closed[o] = open[o] == 0 || ctx.solid[o];
    // The operands' triangle trees: the proof searches each against itself,
    // the solid path pairs of them. Built only when every operand can end up
    // solid (promised, or closed and to be proven); otherwise the proof
    // builds its own.
    std::optional<core::OperandTrees> trees;
    bool may_all_be_solid = options.solid_path;
    for (std::size_t o = 0; o < operands.size(); ++o)
      may_all_be_solid &= ctx.solid[o] || (options.detect_solid && open[o] == 0);
    if (may_all_be_solid) arena.execute([&] { trees = core::build_operand_trees(in.operand_begin, grid.corners); });
    // The leaves' diagonal extents serve the two broad phases only (the
    // proof's contact searches, the partner search): freed when the last of
    // them ends, before the direct route's peak (32 bytes per input triangle).
    std::atomic<int> broad_phases{1};  // the partner search; the proof adds itself
    const auto broad_phase_done = [&] {
      if (broad_phases.fetch_sub(1) != 1) return;
      trees->diagonals = {};
    };
    // With every operand possibly solid, the solid path starts alongside the
    // proof, on the premise the proof is about to establish: a small input's
    // proof and solve are chains of short loops and serial steps that leave
    // the second thread idle (perf on pair034: 28% of its time), so two
    // independent tasks keep the threads busier than either alone. Same
    // inputs as after the proof, so the same result; a failed proof abandons
    // the run (solve_solid's `abandon`) and the general path solves as before.
    // The solid path, all operands solid: with two operands that meet in
    // general position, the result's mesh straight from the intersection
    // curve (direct_mesh.hpp); otherwise its pieces, for the mesh stage.
    if (topology) topology->by_triangle = grid.vertex_ids;
    const bool direct_allowed = topology && operands.size() == 2 && options.output == BooleanOptions::Output::Triangles;
    // A speculative run (`abandon` given) bounds its partner search: where
    // the operands' triangles crowd each other by the hundreds (the sliver
    // pile's twin rods), the search would hold a thread for the whole proof,
    // which then usually fails; past the budget it gives up and, if the
    // proof passes, runs again afterwards (with the leaf diagonals, kept).
    const auto solid_route = [&](const core::SolveContext& c, const std::atomic<bool>* abandon) {
      SolidRoute route;
      const std::atomic<bool> never{false};
      const std::atomic<bool>& stop = abandon ? *abandon : never;
      const std::size_t n = grid.corners.size();
      const std::size_t budget = abandon ? core::kSpeculativePartnersPerTriangle * n + core::kSpeculativeAllowance : SIZE_MAX;
      const core::Partners partners = core::find_partners(grid, *trees, n, stop, budget);
      if (partners.gave_up) {
        route.gave_up = true;
        return route;
      }
      broad_phase_done();
      if (stop.load()) return route;
      if (direct_allowed)
        route.mesh = core::direct_solid_mesh(grid, root.box(), c, *trees, partners, q, sources, *topology, stop);
      if (!route.mesh && !stop.load())
        route.polys = core::solve_solid(grid, root.box(), c, *trees, abandon, &partners);
      return route;
    };
    SolidRoute speculative;
    bool speculated = false;
    if (options.detect_solid) {
      // Closed operands not promised solid are proven solid (or not) exactly,
      // all at once: a small operand's proof alone cannot keep the threads
      // busy. Open ones were reported above. Findings are recorded in
      // operand order, so warnings do not depend on the schedule.
      std::vector<std::uint32_t> unproven;
      for (std::size_t o = 0; o < operands.size(); ++o)
        if (!ctx.solid[o] && open[o] == 0) unproven.push_back(static_cast<std::uint32_t>(o));
      if (!unproven.empty()) {
        report(options, "solid check", 0.1);
        std::vector<core::SolidFinding> findings(unproven.size());
        std::atomic<bool> disproved{false};
        if (trees) ++broad_phases;
        const auto prove = [&] {
          tbb::parallel_for(std::size_t{0}, unproven.size(), [&](std::size_t k) {
            const std::uint32_t o = unproven[k];
            findings[k] = core::check_solid(root, grid, o, trees ? &*trees : nullptr, &disproved);
            if (findings[k].verdict != core::SolidVerdict::Solid) disproved = true;
          });
          if (trees) broad_phase_done();
          proved = std::chrono::steady_clock::now();
        };
        if (trees && threads > 1) {  // one thread would run them one after the other
          speculated = true;
          core::SolveContext premise = ctx;
          premise.solid.assign(operands.size(), 1);
          arena.execute([&] {
            tbb::parallel_invoke(prove, [&] {
              speculative = solid_route(premise, &disproved);
            });
          });
        } else {
          arena.execute(prove);
        }
        for (std::size_t k = 0; k < unproven.size(); ++k)
          ctx.solid[unproven[k]] = record_proof(findings[k], unproven[k], result);
      }
    }
    for (const char s : ctx.solid) result.stats.solid_operands += s != 0;
    if (topology) topology->solid = ctx.solid;
    if (!speculated) proved = std::chrono::steady_clock::now();
    result.stats.proof_ms = ms_between(setup_done, proved);
    report(options, "solve", 0.2);
    arena.execute([&] {
      // All operands solid: the solid path (solid_route.hpp) needs no
      // subdivision. It declines only where every trace it tried met
      // something degenerately; the subdivision then solves as always.
      const bool all_solid = std::all_of(ctx.solid.begin(), ctx.solid.end(), [](char s) { return s != 0; });
      if (!all_solid) trees.reset();  // the subdivision does not use them
      if (trees) {
        SolidRoute route = speculated && !speculative.gave_up ? std::move(speculative) : solid_route(ctx, nullptr);
        result.stats.solid_path = route.mesh || route.polys;
        if (route.mesh) {
          direct_mesh = std::move(route.mesh);
          result.stats.direct_mesh = true;
          return;
        }
        if (route.polys) {
          polys = std::move(*route.polys);
          return;
        }
      }
      core::SolveOutput solved = core::solve(root.take(), ctx);
      polys = std::move(solved.polys);
      result.stats.merged_triangles = core::merge_whole_triangles(polys);
      core::expand_path_pieces(polys, solved.paths);
    });
  }
  const auto solved = std::chrono::steady_clock::now();
  result.stats.solve_ms = ms_between(proved, solved);
  report(options, "export", 0.9);
  if (options.output == BooleanOptions::Output::Polygons) {
    arena.execute([&] { result.mesh = export_mesh(polys, q, sources, result.provenance, result.stats.dropped_slivers); });
  } else {
    core::MeshOutput m;
    if (direct_mesh) {
      m = std::move(*direct_mesh);
    } else {
      if (topology) {
        topology->by_triangle = grid.vertex_ids;
        topology->manifold_edges = grid.manifold_edges;
      }
      arena.execute([&] { m = core::build_triangle_mesh(polys, q, sources, topology ? &*topology : nullptr); });
    }
    result.mesh = std::move(m.mesh);
    result.provenance = std::move(m.provenance);
    result.stats.tjunctions_resolved = m.stats.tjunctions;
    result.stats.collinear_removed = m.stats.collinear_removed;
    result.stats.regions = m.stats.regions;
    result.stats.fallback_regions = m.stats.fallback_regions;
    result.stats.rounded_degenerate = m.stats.rounded_degenerate;
    result.stats.weld_ms = m.stats.weld_ms;
    result.stats.tjunction_ms = m.stats.tjunction_ms;
    result.stats.regions_ms = m.stats.regions_ms;
    result.stats.triangulate_ms = m.stats.triangulate_ms;
    if (m.stats.fallback_regions)
      result.warnings.push_back(std::to_string(m.stats.fallback_regions) +
                                " planar regions could not be merged and were triangulated piece by piece; the mesh "
                                "may have T-junctions there");
    if (m.stats.rounded_degenerate)
      result.warnings.push_back(std::to_string(m.stats.rounded_degenerate) +
                                " output triangles have zero area after rounding to double (exact result is fine)");
  }
  // Unbuilt output triangles point into grid.corners (soup.hpp): freed only now.
  polys = {};
  grid = {};
  result.stats.output_polygons = result.mesh.face_count();
  result.stats.output_vertices = result.mesh.vertices.size();
  const auto end = std::chrono::steady_clock::now();
  result.stats.output_ms = ms_between(solved, end);
  result.stats.time_ms = ms_between(start, end);
  report(options, "done", 1.0);
  return result;
}

}  // namespace ember
