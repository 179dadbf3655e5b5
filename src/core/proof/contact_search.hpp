#pragma once
// Broad phase of the solid proof's self-contact step (solid_proof.hpp, step
// 1): which pairs of an operand's triangles need the exact contact test.
//
// A bounding-volume hierarchy over the triangles in Hilbert curve order, traversed
// against itself: every triangle sits in exactly one leaf, so every pair of
// overlapping boxes is met exactly once, and a pair of subtrees whose boxes
// are apart is dismissed in one test. A kd-split, which sends a triangle to
// every cell its box reaches and dismisses the repeats by an ownership rule
// only after the box test, examines several times more box pairs than it
// tests on a pile of slivers, in the proof's hottest loop.
#include <cstddef>
#include <optional>
#include <span>

#include "core/search/leaf_diagonals.hpp"
#include "core/support/principal_frame.hpp"
#include "core/search/contact_triangle.hpp"
#include "core/search/triangle_contact.hpp"
#include "core/search/triangle_tree.hpp"

namespace ember::core {

struct ContactSearchResult {
  /// Pairs that meet improperly, counted up to the search's max_pairs.
  std::size_t pairs = 0;
  /// The search passed its work budget (a pile of overlapping slivers): no
  /// verdict. Only when no pair was found: a found pair decides.
  bool gave_up = false;
  /// `pairs` is every pair: the search ran to its end (not stopped at
  /// max_pairs, at its budget, or at its counting budget).
  bool complete = true;
};

/// Counts the pairs of `tris` that meet improperly (triangles_meet_improperly),
/// stopping once max_pairs are found, once about kBudgetPerTriangle box pairs
/// per triangle were examined, or, with a pair found, once about
/// kCountingPerTriangle were (`complete` tells). Each unordered pair is
/// tested at most once, so a search that examines fewer than
/// kCountingPerTriangle box pairs per triangle in all (as ordinary meshes
/// do) and ends below max_pairs counts exactly, whatever the
/// thread count. Beyond that, whether and how many pairs were found before
/// the search stopped depends on the schedule; every answer with a pair
/// means "not solid" and one without gives no verdict, so only the report
/// (count, reason) can differ, never the Boolean's path or output. Parallel
/// (oneTBB) in the caller's arena.
/// `tree`, if given, is the tree over tris' boxes (TriangleTree(box_of(tris[i].p)...)), built once for the proof and
/// the solid path; `diagonals`, if given with it, its leaves' diagonal extents (OperandTrees). `found_one`, if given,
/// is set when the first pair is found (the count goes on).
ContactSearchResult find_contacts(std::span<const ContactTriangle> tris, std::size_t max_pairs,
                                  const TriangleTree* tree = nullptr, std::atomic<bool>* found_one = nullptr,
                                  const LeafDiagonals* diagonals = nullptr);

/// The frame whose extents find_contacts adds to its filters
/// (leaf_frame_extents.hpp): the principal frame of the triangles' corners,
/// where a sample of them, queried against `tree` (over tris' boxes), shows
/// the frame's extents apart for enough of the box pairs that the diagonals
/// leave (contact_search.cpp: kFramePairsPerTriangle); otherwise none.
/// Deterministic (a fixed sample). Public for its tests.
std::optional<FrameAxes> sliver_frame(std::span<const ContactTriangle> tris, const TriangleTree& tree);

/// The work budget: box pairs examined per triangle (plus a fixed allowance
/// for small inputs) before the search gives up; the pairs of tree nodes
/// whose frame extents are apart (sliver_frame) are not examined and not
/// counted. The budget lies well above what ordinary meshes examine per
/// triangle, and above what a solid operand of slivers examines without its
/// frame, so that such an operand is not sent down the general path, which
/// costs it several times the Boolean's time; a self-intersecting pile of
/// slivers may pass it without its frame (docs/design.md, "Solid proof").
inline constexpr std::size_t kBudgetPerTriangle = 2048;

/// Once a pair is found the verdict is decided; the search goes on only to
/// count (for the report), and stops counting past this many box pairs per
/// triangle (above what ordinary meshes examine in all, so their counts stay
/// complete): a self-intersecting pile of slivers would otherwise count its
/// pairs to the full budget, a large part of its Boolean's time.
inline constexpr std::size_t kCountingPerTriangle = 512;

}  // namespace ember::core
