// Solid-operand proof (see solid_proof.hpp): pair search for self-contacts
// (contact_search.hpp), manifold components, one classification trace per
// component.
#include "core/proof/solid_proof.hpp"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <atomic>
#include <cassert>

#include "core/model/components.hpp"
#include "core/proof/contact_search.hpp"
#include "core/search/operand_trees.hpp"
#include "core/support/parallel_select.hpp"
#include "core/route/general/leaf.hpp"
#include "core/route/general/root_problem.hpp"
#include "core/route/solid/solid_trace.hpp"
#include "core/proof/vertex_stars.hpp"
#include "ember/boolean.hpp"

namespace ember::core {

namespace {

/// The ids of the operand's polygons, in soup order, selected in parallel
/// (a serial scan of a large input's root soup, tens of megabytes, would be
/// a long stretch of each operand's proof at any thread count).
FillVector<std::uint32_t> operand_members(const Soup& soup, std::uint32_t operand) {
  return parallel_select<std::uint32_t>(
      soup.size(), [&](std::size_t i) { return soup[i].operand == operand; },
      [&](std::size_t i) { return soup[i].id; });
}

}  // namespace

SolidFinding check_solid(RootProblem& root, const GridTriangles& grid, std::uint32_t operand, const OperandTrees* trees,
                         std::atomic<bool>* intersecting) {
  assert(grid.normals.size() == grid.corners.size());
  // With the trees, the operand's triangles are its range of ids; without,
  // the proof scans the soup anyway (below), so it is built now.
  FillVector<std::uint32_t> members;
  if (trees) {
    const std::uint32_t first = root.operand_begin()[operand];
    members.resize(root.operand_begin()[operand + 1] - first);  // every entry written here
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, members.size(), 16384),
                      [&](const tbb::blocked_range<std::size_t>& r) {
                        for (std::size_t i = r.begin(); i != r.end(); ++i)
                          members[i] = first + static_cast<std::uint32_t>(i);
                      });
  } else {
    members = operand_members(root.with_soup().soup, operand);
  }
  if (members.empty()) return {};
  const TriangleTree* tree = trees ? &trees->tree[operand] : nullptr;
  const LeafDiagonals* diagonals = trees ? &trees->diagonals[operand] : nullptr;
  // Counting the contacts (not just finding one) costs at most one full
  // search, the price of proving a solid operand; the count tells the user why.
  FillVector<ContactTriangle> tris(members.size());  // every entry written below
  tbb::parallel_for(
      tbb::blocked_range<std::size_t>(0, members.size(), 4096), [&](const tbb::blocked_range<std::size_t>& r) {
        for (std::size_t i = r.begin(); i != r.end(); ++i)
          tris[i] = contact_triangle(grid.corners[members[i]], grid.normals[members[i]], grid.vertex_ids[members[i]]);
      });
  // tris holds all of the operand's triangles, as a star must. They are
  // the grid's triangles members[0] .. members[0] + size - 1 (an operand's
  // polygons are consecutive in the root soup), whose neighbours are stars'
  // next triangles; were they not consecutive, ids outside would count as no
  // neighbour and certify nothing, never too much.
  const bool consecutive = members.back() - members.front() + 1 == members.size();
  certify_embedded_stars(tris,
                         consecutive ? std::span<const std::array<std::uint32_t, 3>>(
                                           grid.neighbors.data() + members.front(), members.size())
                                     : std::span<const std::array<std::uint32_t, 3>>(),
                         members.front());
  if (tree && tree->size() != tris.size()) tree = nullptr;  // not this operand's: build one (and its diagonals)
  const ContactSearchResult contacts =
      find_contacts(tris, OperandReport::kMaxReportedPairs, tree, intersecting, diagonals);
  tris = {};
  if (contacts.pairs > 0) return {SolidVerdict::SelfIntersecting, contacts.pairs, 0, contacts.complete};
  if (contacts.gave_up) return {SolidVerdict::TooComplex, 0, 0};
  // One representative per component across manifold edges: its smallest
  // id, the first member in order.
  // (Selected in parallel: a serial pass over the members is a stretch of
  // one thread's work.)
  FillVector<std::uint32_t> reps;
  const auto member = [&](std::size_t i) { return members[i]; };
  if (consecutive) {  // the operand's range of ids alone
    const FillVector<std::uint32_t> component = neighbour_components(grid, members.front(), members.size());
    reps = parallel_select<std::uint32_t>(
        members.size(), [&](std::size_t i) { return component[i] == members[i]; }, member);
  } else {
    std::vector<char> keep(grid.neighbors.size(), 0);
    for (const std::uint32_t m : members) keep[m] = 1;
    const FillVector<std::uint32_t> component = neighbour_components(grid, keep);
    reps = parallel_select<std::uint32_t>(
        members.size(), [&](std::size_t i) { return component[members[i]] == members[i]; }, member);
  }
  // With the operand's tree (its item i is triangle members.front() + i),
  // one tree query per trace; a trace that found no non-degenerate path
  // there, or a proof without a tree, scans the root soup (classify_polygon):
  // both answers are exact, so the verdict is the same either way. Each scan
  // reads the whole soup a few times: their total work is bounded (an
  // operand of many components, past the bound, is not proven without a
  // tree, and its failed tree traces are not retried).
  const TriangleTree* own_tree = consecutive ? tree : nullptr;
  constexpr std::size_t kScanBudget = std::size_t{1} << 25;
  const bool scans_affordable = reps.size() <= 8 || reps.size() * grid.corners.size() <= kScanBudget;
  if (!own_tree && !scans_affordable) return {SolidVerdict::TooComplex, 0, 0};
  std::vector<SolidVerdict> verdict(reps.size(), SolidVerdict::Solid);
  tbb::parallel_for(std::size_t{0}, reps.size(), [&](std::size_t c) {
    // The soup's polygon for it (unbuilt, as every root polygon is here).
    const SoupPolygon rep = unbuilt_triangle(grid.corners[reps[c]], reps[c], operand);
    int front = 0, back = 0;
    bool traced = false;
    if (own_tree) {
      TraceScratch sc;
      Polygon built;
      traced =
          own_winding_from_outside(grid.corners, *own_tree, members.front(), root.box(), root.operands(),
                                   built_polygon(rep, built), operand, std::uint64_t{rep.id} << 20, front, back, sc);
    }
    if (!traced && scans_affordable) {
      Wnv w_front, w_back;
      const Subproblem& full = root.with_soup();
      traced = classify_polygon(full, full.soup[reps[c]], w_front, w_back);
      if (traced) front = w_front[operand], back = w_back[operand];
    }
    if (!traced) {
      verdict[c] = SolidVerdict::Unclassified;
    } else if (front != 0 || back != 1) {
      verdict[c] = SolidVerdict::WrongWinding;
    }
  });
  SolidFinding finding;
  finding.misoriented_components =
      static_cast<std::size_t>(std::count(verdict.begin(), verdict.end(), SolidVerdict::WrongWinding));
  if (finding.misoriented_components > 0) {
    finding.verdict = SolidVerdict::WrongWinding;
  } else if (std::count(verdict.begin(), verdict.end(), SolidVerdict::Unclassified) > 0) {
    finding.verdict = SolidVerdict::Unclassified;
  }
  return finding;
}

}  // namespace ember::core
