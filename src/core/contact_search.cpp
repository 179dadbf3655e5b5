// Self-contact broad phase (contact_search.hpp): a Morton-ordered BVH with
// fixed-size leaves in an implicit complete binary tree, traversed against
// itself.
#include "core/contact_search.hpp"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_group.h>

#include <algorithm>
#include <atomic>
#include <bit>
#include <cstdint>
#include <limits>
#include <vector>

#include "core/sort_pairs.hpp"

namespace ember::core {

namespace {

// Grid coordinates satisfy |x| <= 2^25 (kCoordLimit): boxes fit int32.
static_assert(kCoordLimit <= (std::int64_t{1} << 25), "int32 boxes and the Morton code below assume |x| <= 2^25");

struct Box32 {
  std::array<std::int32_t, 3> lo{std::numeric_limits<std::int32_t>::max(), std::numeric_limits<std::int32_t>::max(),
                                 std::numeric_limits<std::int32_t>::max()};
  std::array<std::int32_t, 3> hi{std::numeric_limits<std::int32_t>::min(), std::numeric_limits<std::int32_t>::min(),
                                 std::numeric_limits<std::int32_t>::min()};
  // Default: empty (lo > hi), overlaps nothing.

  void add(const Box32& b) {
    for (int a = 0; a < 3; ++a) {
      lo[a] = std::min(lo[a], b.lo[a]);
      hi[a] = std::max(hi[a], b.hi[a]);
    }
  }
};

/// Closed boxes meet (touching counts: triangles that only touch must be tested).
bool overlap(const Box32& a, const Box32& b) {
  return a.lo[0] <= b.hi[0] && b.lo[0] <= a.hi[0] && a.lo[1] <= b.hi[1] && b.lo[1] <= a.hi[1] &&
         a.lo[2] <= b.hi[2] && b.lo[2] <= a.hi[2];
}

Box32 box_of(const std::array<IntPoint, 3>& t) {
  Box32 b;
  for (const IntPoint& p : t) {
    const std::int64_t c[3] = {p.x, p.y, p.z};
    for (int a = 0; a < 3; ++a) {
      b.lo[a] = std::min(b.lo[a], static_cast<std::int32_t>(c[a]));
      b.hi[a] = std::max(b.hi[a], static_cast<std::int32_t>(c[a]));
    }
  }
  return b;
}

/// 21 bits per axis of the box centre, interleaved: neighbours in space are
/// mostly neighbours in the order, so consecutive triangles make tight leaves.
std::uint64_t morton_key(const Box32& b) {
  const auto spread = [](std::uint64_t v) {  // 21 bits -> every third of 63
    v &= 0x1fffff;
    v = (v | v << 32) & 0x1f00000000ffffULL;
    v = (v | v << 16) & 0x1f0000ff0000ffULL;
    v = (v | v << 8) & 0x100f00f00f00f00fULL;
    v = (v | v << 4) & 0x10c30c30c30c30c3ULL;
    v = (v | v << 2) & 0x1249249249249249ULL;
    return v;
  };
  std::uint64_t key = 0;
  for (int a = 0; a < 3; ++a) {
    // lo + hi is in [-2^26, 2^26]; shifted to [0, 2^27] and cut to 21 bits.
    const std::int64_t twice_centre = std::int64_t{b.lo[a]} + b.hi[a] + (std::int64_t{1} << 26);
    key |= spread(static_cast<std::uint64_t>(std::min<std::int64_t>(twice_centre >> 6, 0x1fffff))) << a;
  }
  return key;
}

class Search {
 public:
  Search(std::span<const ContactTriangle> tris, std::size_t max_pairs) : tris_(tris), max_pairs_(max_pairs) {
    const std::size_t n = tris.size();
    budget_ = kBudgetPerTriangle * n + (std::size_t{1} << 16);
    std::vector<Box32> boxes(n);
    std::vector<std::pair<std::uint64_t, std::uint32_t>> order(n);
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, 4096), [&](const tbb::blocked_range<std::size_t>& r) {
      for (std::size_t i = r.begin(); i != r.end(); ++i) {
        boxes[i] = box_of(tris[i].p);
        order[i] = {morton_key(boxes[i]), static_cast<std::uint32_t>(i)};
      }
    });
    sort_pairs(order);  // keys tie-broken by index: one order for any thread count
    order_.resize(n);
    boxes_.resize(n);
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, 4096), [&](const tbb::blocked_range<std::size_t>& r) {
      for (std::size_t i = r.begin(); i != r.end(); ++i) {
        order_[i] = order[i].second;
        boxes_[i] = boxes[order[i].second];
      }
    });
    build_tree();
  }

  ContactSearchResult run() {
    if (tris_.empty()) return {};
    std::size_t examined = 0;
    self(0, 0, examined);
    flush(examined);
    const std::size_t found = found_.load();
    return {std::min(found, max_pairs_), found == 0 && gave_up_.load()};
  }

 private:
  /// Triangles per leaf: small enough that a leaf's box stays tight, large
  /// enough that the tree costs little next to the triangles (2 nodes each).
  static constexpr std::size_t kLeaf = 8;
  /// Subtrees with at least this many leaves are traversed as parallel tasks.
  static constexpr std::size_t kSpawnLeaves = 64;
  /// Examined pairs are added to the shared count in batches of this size.
  static constexpr std::size_t kFlush = std::size_t{1} << 14;

  /// Implicit complete binary tree in heap order over leaves_ = 2^depth_
  /// slots; node i has children 2i+1, 2i+2, leaf k is node 2^depth_ - 1 + k.
  /// Slots past the last triangle are empty boxes and meet nothing.
  void build_tree() {
    const std::size_t leaves = (tris_.size() + kLeaf - 1) / kLeaf;
    leaves_ = std::bit_ceil(leaves);
    depth_ = std::countr_zero(leaves_);
    nodes_.assign(2 * leaves_ - 1, Box32{});
    const std::size_t first_leaf = leaves_ - 1;
    tbb::parallel_for(std::size_t{0}, leaves, [&](std::size_t k) {
      const std::size_t end = std::min(tris_.size(), (k + 1) * kLeaf);
      for (std::size_t i = k * kLeaf; i < end; ++i) nodes_[first_leaf + k].add(boxes_[i]);
    });
    for (int d = depth_ - 1; d >= 0; --d) {
      const std::size_t first = (std::size_t{1} << d) - 1, count = std::size_t{1} << d;
      tbb::parallel_for(tbb::blocked_range<std::size_t>(first, first + count, 1024),
                        [&](const tbb::blocked_range<std::size_t>& r) {
                          for (std::size_t i = r.begin(); i != r.end(); ++i) {
                            nodes_[i] = nodes_[2 * i + 1];
                            nodes_[i].add(nodes_[2 * i + 2]);
                          }
                        });
    }
  }

  bool done() const {
    return found_.load(std::memory_order_relaxed) >= max_pairs_ || gave_up_.load(std::memory_order_relaxed);
  }
  bool spawns(int depth) const { return (leaves_ >> depth) >= kSpawnLeaves; }

  /// Adds this task's examined pairs to the total; past the budget, give up.
  void flush(std::size_t& examined) {
    if (examined == 0) return;
    if (examined_.fetch_add(examined, std::memory_order_relaxed) + examined > budget_) gave_up_.store(true);
    examined = 0;
  }

  /// All pairs within the subtree of `node` (at `depth`).
  void self(std::size_t node, int depth, std::size_t& examined) {
    if (done()) return;
    if (depth == depth_) {
      leaf_pairs(node, node, examined);
      return;
    }
    const std::size_t l = 2 * node + 1, r = 2 * node + 2;
    if (spawns(depth)) {
      tbb::task_group group;
      group.run([&] { task([&](std::size_t& e) { self(l, depth + 1, e); }); });
      group.run([&] { task([&](std::size_t& e) { self(r, depth + 1, e); }); });
      cross(l, r, depth + 1, examined);
      group.wait();
    } else {
      self(l, depth + 1, examined);
      self(r, depth + 1, examined);
      cross(l, r, depth + 1, examined);
    }
  }

  /// All pairs with one triangle under a and one under b (same depth, disjoint).
  void cross(std::size_t a, std::size_t b, int depth, std::size_t& examined) {
    if (!overlap(nodes_[a], nodes_[b]) || done()) return;
    if (depth == depth_) {
      leaf_pairs(a, b, examined);
      return;
    }
    const std::size_t al = 2 * a + 1, ar = 2 * a + 2, bl = 2 * b + 1, br = 2 * b + 2;
    if (spawns(depth)) {
      tbb::task_group group;
      group.run([&] { task([&](std::size_t& e) { cross(al, bl, depth + 1, e); }); });
      group.run([&] { task([&](std::size_t& e) { cross(al, br, depth + 1, e); }); });
      group.run([&] { task([&](std::size_t& e) { cross(ar, bl, depth + 1, e); }); });
      cross(ar, br, depth + 1, examined);
      group.wait();
    } else {
      cross(al, bl, depth + 1, examined);
      cross(al, br, depth + 1, examined);
      cross(ar, bl, depth + 1, examined);
      cross(ar, br, depth + 1, examined);
    }
  }

  /// Runs f with a counter of its own and flushes it.
  template <typename F>
  void task(F&& f) {
    std::size_t examined = 0;
    f(examined);
    flush(examined);
  }

  /// The exact test for every pair of boxes that meet between leaf nodes a
  /// and b (a == b: the pairs within one leaf).
  void leaf_pairs(std::size_t a, std::size_t b, std::size_t& examined) {
    const std::size_t first_leaf = leaves_ - 1;
    const std::size_t ab = (a - first_leaf) * kLeaf, bb = (b - first_leaf) * kLeaf;
    const std::size_t ae = std::min(tris_.size(), ab + kLeaf), be = std::min(tris_.size(), bb + kLeaf);
    for (std::size_t i = ab; i < ae; ++i) {
      if (!overlap(boxes_[i], nodes_[b])) continue;  // one test instead of one per triangle of b
      for (std::size_t j = a == b ? i + 1 : bb; j < be; ++j) {
        ++examined;
        if (!overlap(boxes_[i], boxes_[j]) || !triangles_meet_improperly(tris_[order_[i]], tris_[order_[j]])) continue;
        if (found_.fetch_add(1) + 1 >= max_pairs_) return;
      }
    }
    if (examined >= kFlush) flush(examined);
  }

  std::span<const ContactTriangle> tris_;
  std::vector<std::uint32_t> order_;  ///< tris_ in Morton order
  std::vector<Box32> boxes_;          ///< the boxes of tris_[order_[i]]
  std::vector<Box32> nodes_;           ///< the tree's boxes, heap order
  std::size_t leaves_ = 1;
  int depth_ = 0;
  std::size_t max_pairs_;
  std::size_t budget_ = 0;
  std::atomic<std::size_t> found_{0};
  std::atomic<std::size_t> examined_{0};
  std::atomic<bool> gave_up_{false};
};

}  // namespace

ContactSearchResult find_contacts(std::span<const ContactTriangle> tris, std::size_t max_pairs) {
  if (tris.size() < 2 || max_pairs == 0) return {};
  return Search(tris, max_pairs).run();
}

}  // namespace ember::core
