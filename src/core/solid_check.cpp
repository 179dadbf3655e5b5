// Solid-operand proof (see solid_check.hpp): pair search for self-contacts,
// manifold components, one classification trace per component.
#include "core/solid_check.hpp"

#include <tbb/parallel_for.h>
#include <tbb/task_group.h>

#include <algorithm>
#include <atomic>
#include <numeric>

#include "core/weld.hpp"
#include "ember/boolean.hpp"

namespace ember::core {

namespace {

struct IntBox {
  std::array<std::int64_t, 3> lo, hi;
};

IntBox box_of(const std::array<IntPoint, 3>& t) {
  IntBox b{{t[0].x, t[0].y, t[0].z}, {t[0].x, t[0].y, t[0].z}};
  for (int v = 1; v < 3; ++v) {
    const std::int64_t c[3] = {t[v].x, t[v].y, t[v].z};
    for (int a = 0; a < 3; ++a) {
      b.lo[a] = std::min(b.lo[a], c[a]);
      b.hi[a] = std::max(b.hi[a], c[a]);
    }
  }
  return b;
}

/// Finds a pair of triangles that meet improperly. A kd-split of space sends
/// each triangle to every cell its box reaches; the pair (i, j) is tested
/// only in the cell holding the corner max(lo_i, lo_j) of the boxes'
/// overlap (cells are half-open), so each overlapping pair is tested once.
class ContactSearch {
 public:
  ContactSearch(const GridTriangles& grid, const std::vector<std::uint32_t>& members) {
    tris_.reserve(members.size());
    boxes_.reserve(members.size());
    for (const std::uint32_t m : members) {
      tris_.push_back(contact_triangle(grid.corners[m], grid.vertex_ids[m]));
      boxes_.push_back(box_of(grid.corners[m]));
    }
  }

  enum class Outcome { None, Found, GaveUp };

  /// Searches until the pairs found reach max_pairs (1: stop at the first).
  Outcome run(std::size_t max_pairs) {
    max_pairs_ = max_pairs;
    std::vector<std::uint32_t> all(tris_.size());
    std::iota(all.begin(), all.end(), 0u);
    IntBox cell{{-2 * kCoordLimit, -2 * kCoordLimit, -2 * kCoordLimit}, {2 * kCoordLimit, 2 * kCoordLimit, 2 * kCoordLimit}};
    search(std::move(all), cell, 0);
    return found_.load() > 0 ? Outcome::Found : (gave_up_.load() ? Outcome::GaveUp : Outcome::None);
  }
  std::size_t pairs_found() const { return std::min(found_.load(), max_pairs_); }

 private:
  static constexpr std::size_t kLeaf = 96;
  static constexpr int kMaxDepth = 64;
  /// A cell whose triangles mostly straddle every split (long slivers all
  /// crossing one region) stops splitting; past this size its all-pairs test
  /// is too costly and the proof gives up ("not solid", never wrong).
  static constexpr std::size_t kMaxLeaf = 2048;

  void search(std::vector<std::uint32_t>&& items, const IntBox& cell, int depth) {
    if (done()) return;
    int axis = 0;
    for (int a = 1; a < 3; ++a)
      if (cell.hi[a] - cell.lo[a] > cell.hi[axis] - cell.lo[axis]) axis = a;
    std::vector<std::uint32_t> left, right;
    const bool splittable = items.size() > kLeaf && depth < kMaxDepth && cell.hi[axis] - cell.lo[axis] >= 2;
    const std::int64_t mid = cell.lo[axis] + (cell.hi[axis] - cell.lo[axis]) / 2;
    if (splittable) {
      // One allocation per child instead of a doubling series: a child holds
      // at most all of the cell's items, and this cell's list is freed below.
      left.reserve(items.size());
      right.reserve(items.size());
      for (const std::uint32_t i : items) {
        if (boxes_[i].lo[axis] < mid) left.push_back(i);
        if (boxes_[i].hi[axis] >= mid) right.push_back(i);
      }
    }
    // A split that leaves nearly every triangle in both halves only doubles the work.
    if (!splittable || 4 * (left.size() + right.size()) > 7 * items.size()) {
      if (items.size() > kMaxLeaf) {
        gave_up_.store(true);
        return;
      }
      test_pairs(items, cell);
      return;
    }
    items = {};
    IntBox lcell = cell, rcell = cell;
    lcell.hi[axis] = mid;
    rcell.lo[axis] = mid;
    if (left.size() + right.size() > 4096) {
      tbb::task_group group;
      group.run([&] { search(std::move(left), lcell, depth + 1); });
      search(std::move(right), rcell, depth + 1);
      group.wait();
    } else {
      search(std::move(left), lcell, depth + 1);
      search(std::move(right), rcell, depth + 1);
    }
  }

  /// All overlapping pairs owned by this cell, by a sweep along x over a
  /// local copy of the boxes (contiguous, sorted by lo.x).
  void test_pairs(std::vector<std::uint32_t>& items, const IntBox& cell) {
    std::sort(items.begin(), items.end(),
              [&](std::uint32_t x, std::uint32_t y) { return boxes_[x].lo[0] < boxes_[y].lo[0]; });
    std::vector<IntBox> boxes(items.size());
    for (std::size_t i = 0; i < items.size(); ++i) boxes[i] = boxes_[items[i]];
    for (std::size_t x = 0; x < items.size(); ++x) {
      const IntBox& bi = boxes[x];
      for (std::size_t y = x + 1; y < items.size(); ++y) {
        const IntBox& bj = boxes[y];
        if (bj.lo[0] > bi.hi[0]) break;  // sorted by lo.x: no later box overlaps bi in x
        if (bj.lo[1] > bi.hi[1] || bi.lo[1] > bj.hi[1] || bj.lo[2] > bi.hi[2] || bi.lo[2] > bj.hi[2]) continue;
        bool owned = true;  // the overlap's low corner lies in this (half-open) cell
        for (int a = 0; a < 3 && owned; ++a) {
          const std::int64_t owner = std::max(bi.lo[a], bj.lo[a]);
          owned = owner >= cell.lo[a] && owner < cell.hi[a];
        }
        if (owned && triangles_meet_improperly(tris_[items[x]], tris_[items[y]]) &&
            found_.fetch_add(1) + 1 >= max_pairs_)
          return;
      }
    }
  }

  std::vector<ContactTriangle> tris_;  ///< the members', in member order
  std::vector<IntBox> boxes_;
  std::size_t max_pairs_ = 1;
  std::atomic<std::size_t> found_{0};
  std::atomic<bool> gave_up_{false};

  bool done() const {
    return found_.load(std::memory_order_relaxed) >= max_pairs_ || gave_up_.load(std::memory_order_relaxed);
  }
};

/// Union-find root with path halving.
std::uint32_t find(std::vector<std::uint32_t>& parent, std::uint32_t x) {
  while (parent[x] != x) x = parent[x] = parent[parent[x]];
  return x;
}

/// Components of the members joined across manifold edges (one use in each
/// direction, on equal grid positions). Returns one representative (the
/// first member in order) per component.
std::vector<std::uint32_t> component_representatives(const GridTriangles& grid,
                                                     const std::vector<std::uint32_t>& members) {
  WeldedTriangles welded;
  welded.ids.reserve(members.size());
  for (const std::uint32_t m : members) {
    welded.ids.push_back(grid.vertex_ids[m]);
    for (const std::uint32_t v : grid.vertex_ids[m]) welded.vertex_count = std::max<std::size_t>(welded.vertex_count, v + 1);
  }
  const std::size_t n = members.size();
  std::vector<std::uint32_t> parent(n);
  std::iota(parent.begin(), parent.end(), 0u);
  for_each_edge(welded, [&](std::span<const EdgeUse> uses) {
    if (uses.size() == 2 && uses[0].forward != uses[1].forward)
      parent[find(parent, uses[0].tri)] = find(parent, uses[1].tri);
  });
  std::vector<std::uint32_t> reps;
  std::vector<char> seen(n, 0);
  for (std::uint32_t t = 0; t < n; ++t) {
    const std::uint32_t r = find(parent, t);
    if (!seen[r]) {
      seen[r] = 1;
      reps.push_back(members[t]);
    }
  }
  return reps;
}

}  // namespace

SolidFinding check_solid(const Subproblem& root, const GridTriangles& grid, std::uint32_t operand) {
  std::vector<std::uint32_t> members;
  for (const SoupPolygon& p : root.soup)
    if (p.operand == operand) members.push_back(p.id);
  if (members.empty()) return {};
  // Counting the contacts (not just finding one) costs at most one full
  // search, the price of proving a solid operand; the count tells the user why.
  ContactSearch search(grid, members);
  switch (search.run(OperandReport::kMaxReportedPairs)) {
    case ContactSearch::Outcome::Found:
      return {SolidVerdict::SelfIntersecting, search.pairs_found(), 0};
    case ContactSearch::Outcome::GaveUp:
      return {SolidVerdict::TooComplex, 0, 0};
    case ContactSearch::Outcome::None:
      break;
  }
  const std::vector<std::uint32_t> reps = component_representatives(grid, members);
  // Each trace scans the whole soup a few times: bound the total work.
  constexpr std::size_t kTraceBudget = std::size_t{1} << 25;
  if (reps.size() > 8 && reps.size() * root.soup.size() > kTraceBudget) return {SolidVerdict::TooComplex, 0, 0};
  std::vector<SolidVerdict> verdict(reps.size(), SolidVerdict::Solid);
  tbb::parallel_for(std::size_t{0}, reps.size(), [&](std::size_t c) {
    Wnv front, back;
    if (!classify_polygon(root, root.soup[reps[c]], front, back)) {
      verdict[c] = SolidVerdict::Unclassified;
    } else if (front[operand] != 0 || back[operand] != 1) {
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
