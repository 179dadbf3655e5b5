// Stage 2 of the Boolean (prove.hpp).
#include "core/proof/prove.hpp"

#include <tbb/parallel_for.h>
#include <tbb/parallel_invoke.h>

#include <atomic>

namespace ember::core {

bool has_operands_to_prove(const SolveSetup& setup) {
  const std::vector<std::size_t>& open = setup.input->open_edges;
  for (std::size_t o = 0; o < open.size(); ++o)
    if (!setup.ctx.solid[o] && open[o] == 0) return true;
  return false;
}

SolidProof prove_solid(SolveSetup& setup, int threads,
                       const std::function<void(const std::atomic<bool>& disproved)>& alongside) {
  SolidProof proof;
  const std::vector<std::size_t>& open = setup.input->open_edges;
  for (std::size_t o = 0; o < open.size(); ++o)
    if (!setup.ctx.solid[o] && open[o] == 0) proof.proven.push_back(static_cast<std::uint32_t>(o));
  proof.findings.resize(proof.proven.size());
  if (proof.proven.empty()) return proof;
  std::atomic<bool> disproved{false};
  if (setup.trees) ++setup.broad_phases;
  const auto prove = [&] {
    tbb::parallel_for(std::size_t{0}, proof.proven.size(), [&](std::size_t k) {
      SolidFinding& f = proof.findings[k];
      f = check_solid(*setup.root, setup.input->triangles.grid, proof.proven[k], setup.trees ? &*setup.trees : nullptr,
                      &disproved);
      if (f.verdict != SolidVerdict::Solid) disproved = true;
    });
    if (setup.trees) setup.broad_phase_done();
    proof.done = std::chrono::steady_clock::now();
  };
  if (setup.trees && threads > 1) {  // one thread would run them one after the other
    proof.speculated = true;
    tbb::parallel_invoke(prove, [&] { alongside(disproved); });
  } else {
    prove();
  }
  return proof;
}

namespace {

SolidStatus status_of(SolidVerdict v) {
  switch (v) {
    case SolidVerdict::Solid: return SolidStatus::Proven;
    case SolidVerdict::SelfIntersecting: return SolidStatus::SelfIntersecting;
    case SolidVerdict::WrongWinding: return SolidStatus::Misoriented;
    case SolidVerdict::TooComplex:
    case SolidVerdict::Unclassified: break;
  }
  return SolidStatus::Undecided;
}

}  // namespace

void record_proof(const SolidProof& proof, SolveSetup& setup, std::vector<OperandReport>& reports,
                  std::vector<std::string>& warnings) {
  for (std::size_t k = 0; k < proof.proven.size(); ++k) {
    const std::uint32_t o = proof.proven[k];
    const SolidFinding& f = proof.findings[k];
    OperandReport& report = reports[o];
    report.self_intersecting_pairs = f.self_intersecting_pairs;
    report.self_intersecting_pairs_complete = f.pairs_complete;
    report.misoriented_components = f.misoriented_components;
    report.solid = status_of(f.verdict);
    setup.ctx.solid[o] = f.verdict == SolidVerdict::Solid;
    if (f.verdict == SolidVerdict::Solid) continue;
    warnings.push_back(operand_name(o) + ": " + describe_solid_check(report) +
                       "; it takes the general path, which is exact but slower "
                       "(CLI: --no-solid-check skips the check)");
  }
}

}  // namespace ember::core
