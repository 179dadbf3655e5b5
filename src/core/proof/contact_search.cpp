// Self-contact broad phase (contact_search.hpp): a Hilbert-ordered BVH with
// fixed-size leaves in an implicit complete binary tree, traversed against
// itself.
#include "core/proof/contact_search.hpp"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_group.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <bit>
#include <cassert>
#include <cstdint>
#include <optional>
#include <vector>

#include "core/search/leaf_diagonals.hpp"
#include "core/search/frame_sample.hpp"
#include "core/search/leaf_frame_extents.hpp"
#include "core/search/leaf_vertex_ids.hpp"
#include "core/search/triangle_tree.hpp"

namespace ember::core {

namespace {

class Search {
 public:
  Search(std::span<const ContactTriangle> tris, std::size_t max_pairs, const TriangleTree* tree,
         std::atomic<bool>* found_one, const LeafDiagonals* diagonals)
      : tris_(tris), diagonals_(diagonals), max_pairs_(max_pairs), found_one_(found_one) {
    const std::size_t n = tris.size();
    budget_ = kBudgetPerTriangle * n + (std::size_t{1} << 16);
    counting_budget_ = kCountingPerTriangle * n + (std::size_t{1} << 16);
    if (!tree) {
      std::vector<Box32> boxes(n);
      tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, 4096), [&](const tbb::blocked_range<std::size_t>& r) {
        for (std::size_t i = r.begin(); i != r.end(); ++i) boxes[i] = box_of(tris[i].p());
      });
      own_tree_ = TriangleTree(boxes);
      tree = &own_tree_;
    }
    tree_ptr_ = tree;
    ids_.emplace(*tree, tris);
    if (!diagonals_) diagonals_ = &own_diagonals_.emplace(*tree, tris);
    if (const std::optional<FrameAxes> frame = sliver_frame(tris, *tree)) frame_.emplace(*tree, tris, *frame);
  }

  ContactSearchResult run() {
    if (tris_.empty()) return {};
    std::size_t examined = 0;
    self(0, 0, examined);
    flush(examined);
    const std::size_t found = found_.load();
    const bool stopped = gave_up_.load() || found >= max_pairs_;
    return {std::min(found, max_pairs_), found == 0 && gave_up_.load(), !stopped};
  }

 private:
  /// Subtrees with at least this many leaves are traversed as parallel tasks.
  static constexpr std::size_t kSpawnLeaves = 64;
  /// Examined pairs are added to the shared count in batches of this size.
  static constexpr std::size_t kFlush = std::size_t{1} << 14;

  const TriangleTree& tree() const { return *tree_ptr_; }

  bool done() const {
    return found_.load(std::memory_order_relaxed) >= max_pairs_ || gave_up_.load(std::memory_order_relaxed);
  }
  bool spawns(int depth) const { return ((tree().first_leaf() + 1) >> depth) >= kSpawnLeaves; }

  /// Adds this task's examined pairs to the total; past the budget, give up,
  /// and past the counting budget too once a pair has decided the verdict.
  void flush(std::size_t& examined) {
    if (examined == 0) return;
    const std::size_t total = examined_.fetch_add(examined, std::memory_order_relaxed) + examined;
    if (total > budget_ || (total > counting_budget_ && found_.load(std::memory_order_relaxed) > 0))
      gave_up_.store(true);
    examined = 0;
  }

  /// All pairs within the subtree of `node` (at `depth`).
  void self(std::size_t node, int depth, std::size_t& examined) {
    if (done()) return;
    if (depth == tree().depth()) {
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

  /// All pairs with one triangle under a and one under b (same depth,
  /// disjoint), if their boxes overlap: tested here, before the call, since
  /// most node pairs do not and the test costs less than a call.
  void cross(std::size_t a, std::size_t b, int depth, std::size_t& examined) {
    if (overlap(tree().node(a), tree().node(b)) && !(frame_ && frame_->nodes_apart(a, b)))
      cross_overlapping(a, b, depth, examined);
  }

  void cross_overlapping(std::size_t a, std::size_t b, int depth, std::size_t& examined) {
    if (done()) return;
    if (!spawns(depth)) {
      // Each combination compiled apart: the frame's test costs nothing where
      // an operand has none (as a branch it would run on every leaf pair).
#if EMBER_WIDE_LANES
      if (wide_)
        return frame_ ? subtree_cross_wide<true>(a, b, depth, examined)
                      : subtree_cross_wide<false>(a, b, depth, examined);
#endif
      return frame_ ? subtree_cross_with<false, true>(a, b, depth, examined)
                    : subtree_cross_with<false, false>(a, b, depth, examined);
    }
    const std::size_t al = 2 * a + 1, ar = 2 * a + 2, bl = 2 * b + 1, br = 2 * b + 2;
    tbb::task_group group;
    group.run([&] { task([&](std::size_t& e) { cross(al, bl, depth + 1, e); }); });
    group.run([&] { task([&](std::size_t& e) { cross(al, br, depth + 1, e); }); });
    group.run([&] { task([&](std::size_t& e) { cross(ar, bl, depth + 1, e); }); });
    cross(ar, br, depth + 1, examined);
    group.wait();
  }

  /// cross_overlapping below the spawning levels, depth first with a stack
  /// of its own (as a recursion, each node pair cost a call with its
  /// spills). Both sides descend together: at most three pending pairs per
  /// level, and a tree of fewer than 2^32 triangles has under 30 levels.
  template <bool Wide, bool Framed>
  [[gnu::always_inline]] inline void subtree_cross_with(std::size_t a, std::size_t b, int depth,
                                                        std::size_t& examined) {
    struct NodePair {
      std::size_t a, b;
      int depth;
    };
    assert(tree().depth() < 40);
    std::array<NodePair, 128> stack;
    std::size_t top = 0;
    stack[top++] = {a, b, depth};
    while (top > 0) {
      const NodePair v = stack[--top];
      if (done()) return;
      if (v.depth == tree().depth()) {
        leaf_pairs_with<Wide, Framed>(v.a, v.b, examined);
        continue;
      }
      // Pushed in reverse: visited in the recursion's order (al-bl, al-br, ar-bl, ar-br).
      for (std::size_t ca = 2 * v.a + 2; ca > 2 * v.a; --ca)
        for (std::size_t cb = 2 * v.b + 2; cb > 2 * v.b; --cb)
          if (overlap(tree().node(ca), tree().node(cb)) && !(Framed && frame_->nodes_apart(ca, cb)))
            stack[top++] = {ca, cb, v.depth + 1};
    }
  }
#if EMBER_WIDE_LANES
  template <bool Framed>
  EMBER_TARGET_AVX2 void subtree_cross_wide(std::size_t a, std::size_t b, int depth, std::size_t& examined) {
    subtree_cross_with<true, Framed>(a, b, depth, examined);
  }
#endif

  /// Runs f with a counter of its own and flushes it.
  template <typename F>
  void task(F&& f) {
    std::size_t examined = 0;
    f(examined);
    flush(examined);
  }

  /// The exact test for every pair of boxes that meet between leaf nodes a
  /// and b (a == b: the pairs within one leaf).
  /// Wide: with the 8-lane leaf tests (wide_lanes.hpp); always inlined, so
  /// that each caller below compiles it for its own instruction set.
  /// Framed: with the frame's extents (frame_ set).
  template <bool Wide, bool Framed>
  [[gnu::always_inline]] inline void leaf_pairs_with(std::size_t a, std::size_t b, std::size_t& examined) {
    const std::size_t ab = tree().leaf_slots(a).first;
    const auto [bb, be] = tree().leaf_slots(b);
    if (ab >= tree().size()) return;  // a leaf past the last triangle (self() does not test its box)
    // a's triangles whose boxes meet b's node box, eight at a time (one test
    // per triangle of a instead of one per pair).
    const unsigned near_b = tree().overlap_mask_in<Wide>(a, tree().node(b));
    // The box pairs examined, for the budget: each such triangle of a against
    // b's slots (within one leaf, the slots after it), counted here at once.
    if (a != b) {
      examined += static_cast<std::size_t>(std::popcount(near_b)) * (be - bb);
    } else {
      for (unsigned m = near_b; m != 0; m &= m - 1) examined += be - std::min(be, ab + std::countr_zero(m) + 1);
    }
    for (unsigned near = near_b; near != 0; near &= near - 1) {
      const std::size_t i = ab + static_cast<std::size_t>(std::countr_zero(near));
      const Box32 box = tree().box(i);
      const std::size_t from = a == b ? i + 1 : bb;
      // Within one leaf only the slots after i. Triangles sharing a vertex
      // whose star is certified embedded never meet improperly
      // (triangles_meet_improperly's first answer): when all three of i's
      // are, its neighbours need no test.
      const ContactTriangle& ti = tris_[tree().item(i)];
      unsigned candidates = tree().overlap_mask_in<Wide>(b, box) & (~0u << (from - bb));
      // Framed: first the extents along the operand's slivers (sliver_frame),
      // which leave few of a sliver pile's box pairs, before the vertex ids
      // are compared.
      if constexpr (Framed)
        if (candidates != 0) candidates &= ~frame_->apart_mask_in<Wide>(b, frame_->extent(i));
      if (candidates == 0) continue;
      const LeafVertexIds::Masks shared = ids_->shared_masks_in<Wide>(b, ti.id);
      if (ti.embedded == 7) candidates &= ~shared.neighbours;
      // Boxes that meet, diagonal extents that do not: long slivers across
      // the axes (most of the pairs the boxes leave there), dismissed for a
      // fraction of the exact test's cost.
      if (candidates != 0) candidates &= ~diagonals_->apart_mask_in<Wide>(b, diagonals_->extent(i));
      if (candidates == 0) continue;
      for (unsigned m = candidates; m != 0; m &= m - 1) {
        const int slot = std::countr_zero(m);
        const ContactTriangle& tj = tris_[tree().item(bb + static_cast<std::size_t>(slot))];
        // Most pairs left share no vertex (nearly all, on most inputs): their
        // test is apart_triangles_meet, without the shared
        // vertex bookkeeping of triangles_meet_improperly (a third of its cost).
        if (!(shared.sharing >> slot & 1u) ? !apart_triangles_meet(ti.p(), ti.n, tj.p(), tj.n)
                                           : !triangles_meet_improperly(ti, tj))
          continue;
        if (found_one_) found_one_->store(true, std::memory_order_relaxed);
        if (found_.fetch_add(1) + 1 >= max_pairs_) return;
      }
    }
    if (examined >= kFlush) flush(examined);
  }

  void leaf_pairs(std::size_t a, std::size_t b, std::size_t& examined) {
#if EMBER_WIDE_LANES
    if (wide_) return frame_ ? leaf_pairs_wide<true>(a, b, examined) : leaf_pairs_wide<false>(a, b, examined);
#endif
    return frame_ ? leaf_pairs_with<false, true>(a, b, examined) : leaf_pairs_with<false, false>(a, b, examined);
  }
#if EMBER_WIDE_LANES
  template <bool Framed>
  EMBER_TARGET_AVX2 void leaf_pairs_wide(std::size_t a, std::size_t b, std::size_t& examined) {
    leaf_pairs_with<true, Framed>(a, b, examined);
  }
#endif

  std::span<const ContactTriangle> tris_;
  TriangleTree own_tree_;  ///< when the caller gave none
  std::optional<LeafVertexIds> ids_;
  std::optional<LeafDiagonals> own_diagonals_;  ///< when the caller gave none
  std::optional<LeafFrameExtents> frame_;       ///< along the slivers (sliver_frame), if any
  const LeafDiagonals* diagonals_;
  const TriangleTree* tree_ptr_ = nullptr;
  std::size_t max_pairs_;
  std::size_t budget_ = 0;
  std::size_t counting_budget_ = 0;
  std::atomic<std::size_t> found_{0};
  std::atomic<std::size_t> examined_{0};
  std::atomic<bool> gave_up_{false};
  std::atomic<bool>* found_one_ = nullptr;
  bool wide_ = cpu_has_avx2();
};

}  // namespace

// An ordinary mesh has a few box pairs per triangle and none of them apart in
// the frame: its sample rejects the frame.
std::optional<FrameAxes> sliver_frame(std::span<const ContactTriangle> tris, const TriangleTree& tree) {
  const auto corners = [&](std::size_t i) -> const std::array<IntPoint, 3>& { return tris[i].p(); };
  FrameAxes frame;
  if (!principal_frame(frame_points(tris.size(), corners), frame)) return std::nullopt;
  std::size_t sampled = 0;
  const std::size_t dismissed =
      frame_dismissals<1>(tris.size(), corners, tree, corners, std::array<FrameAxes, 1>{frame}, true, sampled)[0];
  // Each pair is met from both of its triangles.
  if (static_cast<double>(dismissed) < 2 * kFramePairsPerTriangle * static_cast<double>(sampled)) return std::nullopt;
  return frame;
}

ContactSearchResult find_contacts(std::span<const ContactTriangle> tris, std::size_t max_pairs,
                                  const TriangleTree* tree, std::atomic<bool>* found_one,
                                  const LeafDiagonals* diagonals) {
  if (tris.size() < 2 || max_pairs == 0) return {};
  return Search(tris, max_pairs, tree, found_one, tree ? diagonals : nullptr).run();
}

}  // namespace ember::core
