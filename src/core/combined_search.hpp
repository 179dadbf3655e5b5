#pragma once
// The solid proof's contact searches and the solid path's partner search in
// one traversal (docs/redesign.md, step 7). Both ask which triangles' boxes
// meet: the proof within each operand, the partner search between the two.
// Where the operands lie close together (the bunny pair: a mesh and its
// copy turned by 1 degree) a tree over both operands' triangles meets both
// kinds of pair in the same leaf pairs, visited once: 77.8k leaf pairs
// instead of the three searches' 65k + 55k.
//
// It decides only that case: surfaces that crowd each other, no frame (the
// separate searches keep their frames, which CAD-like operands and the pile
// cases need) and no operand with a pair that meets improperly. Anything
// else answers without partners, and the caller runs the separate searches
// as before, which count and report.
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
/// searches of those with `searched` set, in one traversal. It runs only
/// where the operands' surfaces crowd each other (most triangles of each
/// have a box meeting one of the other's: a mesh and its copy turned a
/// little) and their trees merge (keyed over common cells); elsewhere it
/// returns at once, prepared nothing, and the separate searches cost less.
/// No partners either where a searched operand has two triangles meeting
/// improperly, where the separate searches would use a frame (sliver_frame
/// of a searched operand, partner_frame of the pair) or where the search
/// passed its budget (kCountingPerTriangle box pairs per triangle); those
/// searches then run on what it prepared. `second_vertex_base`: added to
/// the second operand's vertex ids, past every id of the first
/// (InputTopology::operand_base[1]), so no vertex id is in both. The answer
/// does not depend on the schedule. Parallel (oneTBB) in the caller's arena.
/// `trees` are built without diagonals (build_operand_trees); where it
/// declines, they are added for the separate searches, and so are the
/// frames it sampled (OperandTrees::sliver, ::partner), which those
/// searches then need not sample again.
CombinedBroadPhase combined_broad_phase(const GridTriangles& grid, OperandTrees& trees, std::array<bool, 2> searched,
                                        std::uint32_t second_vertex_base);

}  // namespace ember::core
