#pragma once
// Stage 2 of the Boolean (boolean.cpp): closed operands not promised solid
// are proven solid (or not) exactly, all at once: a small operand's proof
// alone cannot keep the threads busy. Open ones were reported by the input
// stage.
#include <chrono>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "core/proof/solid_proof.hpp"
#include "core/route/solve_setup.hpp"

namespace ember::core {

struct SolidProof {
  std::vector<std::uint32_t> proven;           ///< the operands the proof decided, increasing
  std::vector<SolidFinding> findings;          ///< one per entry of `proven`
  bool speculated = false;                     ///< `alongside` ran beside the proof
  std::chrono::steady_clock::time_point done;  ///< when the proof ended
};

/// Some closed operand is not yet held solid: there is something to prove.
bool has_operands_to_prove(const SolveSetup& setup);

/// Proves the closed operands that `setup.ctx` does not hold solid. With the
/// operands' trees and more than one thread, `alongside` runs beside the
/// proof (the solid path on the premise the proof is about to establish),
/// given a flag that is set as soon as some operand is found not solid.
/// Run it inside the Boolean's task arena.
SolidProof prove_solid(SolveSetup& setup, int threads,
                       const std::function<void(const std::atomic<bool>& disproved)>& alongside);

/// Records the proof's findings in the operands' reports, marks the proven
/// operands solid in setup.ctx, and warns for each operand that failed (it
/// changes route and time).
void record_proof(const SolidProof& proof, SolveSetup& setup, std::vector<OperandReport>& reports,
                  std::vector<std::string>& warnings);

}  // namespace ember::core
