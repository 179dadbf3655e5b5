#pragma once
// The solid proof's contact searches and the solid path's partner search in
// one traversal (docs/redesign.md, step 7). Both ask which triangles' boxes
// meet: the proof within each operand, the partner search between the two.
// Where the operands lie close together (the bunny pair: a mesh and its
// copy turned by 1 degree) a tree over both operands' triangles meets both
// kinds of pair in the same leaf pairs, visited once: 77.8k leaf pairs
// instead of the three searches' 65k + 55k.
//
// It decides only the common case: no frame applies (the separate searches
// keep their frames, which the pile cases need) and no operand has a pair
// that meets improperly. Anything else (a frame, a self-intersection, a
// search past its budget) answers nullopt, and the caller runs the separate
// searches as before, which count and report.
#include <array>
#include <optional>
#include <span>

#include "core/operand_trees.hpp"
#include "core/solid_check.hpp"
#include "core/solid_path.hpp"

namespace ember::core {

/// What combined_broad_phase found.
struct CombinedBroadPhase {
  /// The Partners that find_partners would find, where every searched
  /// operand's find_contacts would count no pair; else nullopt.
  std::optional<Partners> partners;
  /// Without partners: every grid triangle prepared for the contact test
  /// (prepare_contact_triangles; the second operand's vertex ids offset),
  /// for the separate searches (check_solid's `prepared`).
  FillVector<ContactTriangle> prepared;
  /// The contact triangles of `operand`, if prepared.
  std::span<const ContactTriangle> of(const OperandTrees& trees, std::size_t operand) const {
    if (prepared.size() != trees.begin.back()) return {};
    return std::span<const ContactTriangle>(prepared).subspan(trees.begin[operand],
                                                              trees.begin[operand + 1] - trees.begin[operand]);
  }
};

/// For two operands (trees.begin has three entries, their trees built over
/// grid's triangles): the meeting pairs of the operands and the contact
/// searches of those with `searched` set, in one traversal. No partners
/// where a searched operand has two triangles meeting improperly, where the
/// separate searches would use a frame (sliver_frame of a searched operand,
/// partner_frame of the pair), or where the search passed its budget
/// (kCountingPerTriangle box pairs per triangle). `second_vertex_base`:
/// added to the second operand's vertex ids, past every id of the first
/// (InputTopology::operand_base[1]), so no vertex id is in both. The answer
/// does not depend on the schedule. Parallel (oneTBB) in the caller's arena.
/// `trees` are built without diagonals (build_operand_trees); where it
/// declines, they are added for the separate searches, and so are the
/// frames it sampled (OperandTrees::sliver, ::partner), which those
/// searches then need not sample again.
CombinedBroadPhase combined_broad_phase(const GridTriangles& grid, OperandTrees& trees, std::array<bool, 2> searched,
                                        std::uint32_t second_vertex_base);

}  // namespace ember::core
