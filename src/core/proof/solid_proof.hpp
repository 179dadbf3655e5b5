#pragma once
// Exact proof that an operand is *solid* in the sense the core's shortcuts
// need (paper Section 4.5.1, NSI + NNC; BooleanOptions::solid): its winding
// number is 0 in front of and 1 behind every one of its triangles.
//
// The proof has three exact steps on the quantized, non-degenerate triangles:
//  1. no self-intersection: any two triangles meet in nothing, a shared
//     vertex, or a shared edge (integer orientation predicates, <= 84 bits);
//  2. components: triangles joined across manifold edges (used once in each
//     direction). By step 1 nothing else comes near such an edge, so the
//     winding number in front of a component is one constant;
//  3. one classification trace per component gives that constant: it must be
//     0 (and 1 behind).
// Every doubt (touching, T-junctions, non-manifold edges, too many
// components for the trace budget, a failed trace) answers "not solid": the
// caller then takes the general path, which is always correct.
#include <atomic>
#include <cstddef>
#include <cstdint>

#include "core/model/grid_triangles.hpp"

namespace ember::core {

class RootProblem;
struct OperandTrees;

enum class SolidVerdict {
  Solid,
  SelfIntersecting,  ///< two triangles meet beyond a shared vertex or edge (or touch)
  WrongWinding,      ///< some component has winding != 0 in front (nested, inverted)
  TooComplex,        ///< beyond the proof's work budget (many components, piles of slivers): not decided
  Unclassified,      ///< no valid trace path (not decided)
};

/// The verdict and, for the user, how much evidence was found against it.
struct SolidFinding {
  SolidVerdict verdict = SolidVerdict::Solid;
  std::size_t self_intersecting_pairs = 0;  ///< counted up to OperandReport::kMaxReportedPairs
  std::size_t misoriented_components = 0;
  bool pairs_complete = true;  ///< self_intersecting_pairs is every pair (ContactSearchResult::complete)
};

/// Decides whether `operand` is solid. `root` is the whole problem (its
/// triangles are grid's, polygon i is triangle i; its reference point is
/// outside everything); its soup is built (RootProblem::with_soup) only where
/// a scan of it is needed: a proof without `trees`, or a trace through the
/// tree that found no non-degenerate path.
/// `trees`, if given, are the operands' triangle trees with their leaves'
/// extents (build_operand_trees over root.operand_begin()).
/// `intersecting`, if given, is set as soon as the search meets the first
/// self-intersection, before the count is complete: the defaults' solid
/// path, started alongside the proof on the premise that every operand is
/// solid, stops on it (solve_solid's `abandon`) and frees its threads.
SolidFinding check_solid(RootProblem& root, const GridTriangles& grid, std::uint32_t operand,
                         const OperandTrees* trees = nullptr, std::atomic<bool>* intersecting = nullptr);

}  // namespace ember::core
