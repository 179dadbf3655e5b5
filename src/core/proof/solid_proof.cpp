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

#include "core/proof/contact_search.hpp"
#include "core/search/operand_trees.hpp"
#include "core/support/parallel_select.hpp"
#include "core/route/general/root_problem.hpp"
#include "core/route/solid/solid_trace.hpp"
#include "core/proof/vertex_stars.hpp"
#include "ember/boolean.hpp"

namespace ember::core {

namespace {

// A concurrent union-find over triangle ids. Every parent pointer points to
// a smaller or equal id, so a root is the smallest id of its tree and the
// final roots are each component's smallest id, whatever the schedule: the
// same answer as a serial pass, computed in parallel (the serial pass, run
// by the proof and again by the solid path, was 2% of pair001's
// instructions, all of it serial). Links are compare-and-swaps on roots;
// path halving stores an ancestor (a smaller id of the same set), which is
// correct whenever it lands.
using Parents = FillVector<std::uint32_t>;

std::uint32_t load(Parents& parent, std::uint32_t x) {
  return std::atomic_ref<std::uint32_t>(parent[x]).load(std::memory_order_relaxed);
}

/// Root of x, halving the path on the way.
std::uint32_t find(Parents& parent, std::uint32_t x) {
  for (std::uint32_t p = load(parent, x); p != x; p = load(parent, x)) {
    const std::uint32_t g = load(parent, p);
    if (g != p) std::atomic_ref<std::uint32_t>(parent[x]).store(g, std::memory_order_relaxed);
    x = p;
  }
  return x;
}

/// Joins the sets of a and b: the larger root is linked below the smaller.
void unite(Parents& parent, std::uint32_t a, std::uint32_t b) {
  for (;;) {
    std::uint32_t ra = find(parent, a), rb = find(parent, b);
    if (ra == rb) return;
    if (ra < rb) std::swap(ra, rb);
    // ra is the larger root; it may have been linked meanwhile: then retry.
    std::uint32_t expected = ra;
    if (std::atomic_ref<std::uint32_t>(parent[ra]).compare_exchange_strong(expected, rb, std::memory_order_relaxed))
      return;
  }
}

/// Calls f(i, j) for each kept local triangle i in [begin, end) and each
/// kept neighbour j > i in [0, count): triangle first + i of the grid, its
/// neighbours mutual (both ends of a manifold edge), so every pair once.
template <typename Keep, typename F>
void each_kept_pair(const GridTriangles& grid, std::uint32_t first, std::size_t count, const Keep& keep,
                    std::size_t begin, std::size_t end, F&& f) {
  for (std::size_t i = begin; i != end; ++i) {
    if (!keep(first + i)) continue;
    for (const std::uint32_t n : grid.neighbors[first + i]) {
      const std::uint32_t j = n - first;  // wraps past count for ids below first and kNoNeighbor
      if (j < count && j > i && keep(n)) f(static_cast<std::uint32_t>(i), j);
    }
  }
}

/// The serial pass, for one thread: a flood fill from each kept triangle
/// not yet reached, in ascending order, so each component's first triangle
/// is its smallest id (the union-find's answer; the fill costs about half its
/// instructions, and the concurrent union-find 1.5x its own).
template <typename Keep>
Parents serial_components(const GridTriangles& grid, std::uint32_t first, std::size_t count, const Keep& keep) {
  constexpr std::uint32_t kUnreached = UINT32_MAX;
  Parents root(count, kUnreached);
  std::vector<std::uint32_t> stack;
  for (std::size_t s = 0; s < count; ++s) {
    if (root[s] != kUnreached || !keep(first + s)) continue;
    root[s] = static_cast<std::uint32_t>(s);
    stack.push_back(static_cast<std::uint32_t>(s));
    while (!stack.empty()) {
      const std::uint32_t t = stack.back();
      stack.pop_back();
      for (const std::uint32_t n : grid.neighbors[first + t]) {
        const std::uint32_t j = n - first;  // wraps past count for ids below first and kNoNeighbor
        if (j < count && root[j] == kUnreached && keep(n)) {
          root[j] = static_cast<std::uint32_t>(s);
          stack.push_back(j);
        }
      }
    }
  }
  return root;
}

/// Components of the kept triangles first .. first + count - 1, joined
/// across manifold edges inside that range: per kept triangle first + i,
/// entry i is the smallest id of its component.
template <typename Keep>
FillVector<std::uint32_t> components(const GridTriangles& grid, std::uint32_t first, std::size_t count,
                                      const Keep& keep) {
  Parents parent;
  if (tbb::this_task_arena::max_concurrency() == 1) {
    parent = serial_components(grid, first, count, keep);
  } else {
    parent.resize(count);  // every entry written below (a value-initializing resize was a serial pass)
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, count, 4096), [&](const tbb::blocked_range<std::size_t>& r) {
      for (std::size_t i = r.begin(); i != r.end(); ++i) parent[i] = static_cast<std::uint32_t>(i);
    });
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, count, 1024), [&](const tbb::blocked_range<std::size_t>& r) {
      each_kept_pair(grid, first, count, keep, r.begin(), r.end(),
                     [&](std::uint32_t i, std::uint32_t j) { unite(parent, i, j); });
    });
    // Every root is final now: point each kept entry at it (find only reads
    // and halves paths, which stays correct under the concurrent halving).
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, count, 4096), [&](const tbb::blocked_range<std::size_t>& r) {
      for (std::size_t i = r.begin(); i != r.end(); ++i) {
        if (!keep(first + i)) continue;
        const std::uint32_t root = find(parent, static_cast<std::uint32_t>(i));
        std::atomic_ref<std::uint32_t>(parent[i]).store(root, std::memory_order_relaxed);
      }
    });
  }
  if (first != 0)
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, count, 16384), [&](const tbb::blocked_range<std::size_t>& r) {
      for (std::size_t i = r.begin(); i != r.end(); ++i) parent[i] += first;
    });
  return parent;
}

}  // namespace

FillVector<std::uint32_t> neighbour_components(const GridTriangles& grid, std::span<const char> keep) {
  return components(grid, 0, keep.size(), [&](std::size_t i) { return keep[i] != 0; });
}

FillVector<std::uint32_t> neighbour_components(const GridTriangles& grid, std::uint32_t first, std::size_t count) {
  return components(grid, first, count, [](std::size_t) { return true; });
}

namespace {

/// The ids of the operand's polygons, in soup order, selected in parallel
/// (a serial scan of the 1.08M-triangle union's root soup, 86 MB, was
/// ~20 ms of each operand's proof at any thread count).
FillVector<std::uint32_t> operand_members(const Soup& soup, std::uint32_t operand) {
  return parallel_select<std::uint32_t>(
      soup.size(), [&](std::size_t i) { return soup[i].operand == operand; }, [&](std::size_t i) { return soup[i].id; });
}

}  // namespace

SolidFinding check_solid(RootProblem& root, const GridTriangles& grid, std::uint32_t operand,
                         const OperandTrees* trees, std::atomic<bool>* intersecting) {
  assert(grid.normals.size() == grid.corners.size());
  // With the trees, the operand's triangles are its range of ids; without,
  // the proof scans the soup anyway (below), so it is built now.
  FillVector<std::uint32_t> members;
  if (trees) {
    const std::uint32_t first = root.operand_begin()[operand];
    members.resize(root.operand_begin()[operand + 1] - first);  // every entry written here
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, members.size(), 16384), [&](const tbb::blocked_range<std::size_t>& r) {
      for (std::size_t i = r.begin(); i != r.end(); ++i) members[i] = first + static_cast<std::uint32_t>(i);
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
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, members.size(), 4096),
                    [&](const tbb::blocked_range<std::size_t>& r) {
                      for (std::size_t i = r.begin(); i != r.end(); ++i)
                        tris[i] = contact_triangle(grid.corners[members[i]], grid.normals[members[i]],
                                                   grid.vertex_ids[members[i]]);
                    });
  // tris holds all of the operand's triangles, as a star must. They are
  // the grid's triangles members[0] .. members[0] + size - 1 (an operand's
  // polygons are consecutive in the root soup), whose neighbours are stars'
  // next triangles; were they not consecutive, ids outside would count as no
  // neighbour and certify nothing, never too much.
  const bool consecutive = members.back() - members.front() + 1 == members.size();
  certify_embedded_stars(tris,
                         consecutive ? std::span<const std::array<std::uint32_t, 3>>(grid.neighbors.data() + members.front(),
                                                                                      members.size())
                                     : std::span<const std::array<std::uint32_t, 3>>(),
                         members.front());
  if (tree && tree->size() != tris.size()) tree = nullptr;  // not this operand's: build one (and its diagonals)
  const ContactSearchResult contacts = find_contacts(tris, OperandReport::kMaxReportedPairs, tree, intersecting, diagonals);
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
    reps = parallel_select<std::uint32_t>(members.size(), [&](std::size_t i) { return component[i] == members[i]; }, member);
  } else {
    std::vector<char> keep(grid.neighbors.size(), 0);
    for (const std::uint32_t m : members) keep[m] = 1;
    const FillVector<std::uint32_t> component = neighbour_components(grid, keep);
    reps = parallel_select<std::uint32_t>(members.size(), [&](std::size_t i) { return component[members[i]] == members[i]; },
                                          member);
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
      traced = own_winding_from_outside(grid.corners, *own_tree, members.front(), root.box(), root.operands(),
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
  finding.misoriented_components = static_cast<std::size_t>(std::count(verdict.begin(), verdict.end(), SolidVerdict::WrongWinding));
  if (finding.misoriented_components > 0) {
    finding.verdict = SolidVerdict::WrongWinding;
  } else if (std::count(verdict.begin(), verdict.end(), SolidVerdict::Unclassified) > 0) {
    finding.verdict = SolidVerdict::Unclassified;
  }
  return finding;
}

}  // namespace ember::core
