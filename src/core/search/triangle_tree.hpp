#pragma once
// A bounding-volume hierarchy over grid triangles: the triangles in Hilbert
// curve order of their box centres, kLeaf to a leaf of an implicit complete binary
// tree (heap order, built bottom-up in parallel). Every triangle sits in
// exactly one leaf, so a traversal meets every pair of overlapping boxes
// exactly once. Used by the solid proof's self-contact search
// (contact_search.hpp) and by the solid path's broad phase and traces
// (solid_route.hpp) through OperandTrees (operand_trees.hpp).
#if defined(__SSE2__)
#include <emmintrin.h>
#endif

#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <bit>
#include <cassert>
#include <cmath>
#include <cstdint>
#include <limits>
#include <span>
#include <vector>

#include "core/support/wide_lanes.hpp"
#include "geometry/plane.hpp"

namespace ember::core {

// Grid coordinates satisfy |x| <= 2^25 (kCoordLimit): boxes fit int32.
static_assert(kCoordLimit <= (std::int64_t{1} << 25), "int32 boxes and the curve keys assume |x| <= 2^25");

/// A closed integer box; default-constructed empty (lo > hi), meeting nothing.
struct Box32 {
  std::array<std::int32_t, 3> lo{std::numeric_limits<std::int32_t>::max(), std::numeric_limits<std::int32_t>::max(),
                                 std::numeric_limits<std::int32_t>::max()};
  std::array<std::int32_t, 3> hi{std::numeric_limits<std::int32_t>::min(), std::numeric_limits<std::int32_t>::min(),
                                 std::numeric_limits<std::int32_t>::min()};

  void add(const Box32& b) {
    for (int a = 0; a < 3; ++a) {
      lo[a] = std::min(lo[a], b.lo[a]);
      hi[a] = std::max(hi[a], b.hi[a]);
    }
  }
};

/// Closed boxes meet (touching counts: triangles that only touch must be tested).
inline bool overlap(const Box32& a, const Box32& b) {
  return a.lo[0] <= b.hi[0] && b.lo[0] <= a.hi[0] && a.lo[1] <= b.hi[1] && b.lo[1] <= a.hi[1] && a.lo[2] <= b.hi[2] &&
         b.lo[2] <= a.hi[2];
}

Box32 box_of(const std::array<IntPoint, 3>& t);

/// The place of cell (x, y, z) (10 bits each) along a 3D Hilbert curve
/// through the 2^30 cells (the tree's order; 30 bits).
std::uint32_t hilbert_key(std::uint32_t x, std::uint32_t y, std::uint32_t z);

/// True if the box lies clearly on one side of the plane through grid point
/// o with normal n (a grid triangle's grid_normal, |n_k| < 2^53): all its
/// corners strictly on one side. A filter in double: it may miss a box that
/// is beside the plane, never the reverse.
bool box_clearly_beside(const Box32& box, const IntPoint& o, const std::array<std::int64_t, 3>& n);

/// Queries never span the whole int32 range along x. The last leaf's
/// unused slots hold empty boxes (lo = INT32_MAX, hi = INT32_MIN), which then
/// meet no query, so the leaf masks need no count of used slots (computing
/// it per mask would add work to every leaf test). Grid boxes lie
/// within +-2^25; enclosing_box clamps to +-kQueryLimit.
inline constexpr std::int32_t kQueryLimit = std::int32_t{1} << 30;
static_assert(kCoordLimit < kQueryLimit && kQueryLimit < std::numeric_limits<std::int32_t>::max(),
              "clamping a query to +-kQueryLimit keeps every grid box it meets, and stays in range");
inline bool query_in_range(const Box32& q) {
  return q.lo[0] > std::numeric_limits<std::int32_t>::min() || q.hi[0] < std::numeric_limits<std::int32_t>::max();
}

/// The smallest integer box containing the double box [lo, hi], clamped to
/// +-kQueryLimit (beyond the grid: no grid box it meets is lost), for
/// queries with a conservative double box.
Box32 enclosing_box(const std::array<double, 3>& lo, const std::array<double, 3>& hi);

class TriangleTree {
 public:
  /// Triangles per leaf: small enough that a leaf's box stays tight, large
  /// enough that the tree costs little next to the triangles (2 nodes each).
  static constexpr std::size_t kLeaf = 8;

  TriangleTree() = default;
  /// The tree over triangles 0 .. boxes.size() - 1 with these boxes.
  /// Parallel (oneTBB); the result does not depend on the thread count.
  explicit TriangleTree(std::span<const Box32> boxes);

  std::size_t size() const { return item_.size(); }
  bool empty() const { return item_.empty(); }
  /// The triangle in slot `slot` (curve order), and its box.
  std::uint32_t item(std::size_t slot) const { return item_[slot]; }
  /// Per-leaf data laid out like the leaves' boxes: one Block per filled
  /// leaf, `blocks` resized and each block's slot s written in parallel by
  /// fill(block, s, item) (item: the triangle in that slot, or kNoItem for
  /// the empty slots of the last leaf).
  static constexpr std::uint32_t kNoItem = UINT32_MAX;
  /// (A FillVector's blocks are first touched there, in parallel.)
  template <typename Block, typename Alloc, typename Fill>
  void fill_leaf_blocks(std::vector<Block, Alloc>& blocks, Fill&& fill) const {
    blocks.resize((size() + kLeaf - 1) / kLeaf);
    tbb::parallel_for(std::size_t{0}, blocks.size(), [&](std::size_t k) {
      for (std::size_t s = 0; s < kLeaf; ++s)
        fill(blocks[k], s, k * kLeaf + s < size() ? item(k * kLeaf + s) : kNoItem);
    });
  }
  Box32 box(std::size_t slot) const {
    const LeafBlock& b = block_[slot / kLeaf];
    const std::size_t k = slot % kLeaf;
    return {{b.lo[0][k], b.lo[1][k], b.lo[2][k]}, {b.hi[0][k], b.hi[1][k], b.hi[2][k]}};
  }
  /// Bit k set iff the box of the leaf's k-th slot meets `query` (slots past
  /// the last triangle never do, the query being in range: query_in_range):
  /// all kLeaf tests at once, without branches.
  /// The leaf must hold a triangle (leaf_slots(leaf_node).first < size()):
  /// the leaves past the last one have no coordinate block.
  /// Always inlined: it is the inner step of every leaf loop, and the
  /// compiler's own choice flips with unrelated changes to its callers.
  [[gnu::always_inline]] inline unsigned overlap_mask(std::size_t leaf_node, const Box32& query) const;
  /// The same without vector instructions (what overlap_mask is where SSE2 is missing).
  unsigned overlap_mask_portable(std::size_t leaf_node, const Box32& query) const;
#if EMBER_WIDE_LANES
  /// The same in eight lanes at once (wide_lanes.hpp): only where cpu_has_avx2().
  EMBER_TARGET_AVX2 unsigned overlap_mask_avx2(std::size_t leaf_node, const Box32& query) const;
#endif
  /// overlap_mask, in eight lanes when Wide (only where cpu_has_avx2()).
  template <bool Wide>
  [[gnu::always_inline]] unsigned overlap_mask_in(std::size_t leaf_node, const Box32& query) const {
#if EMBER_WIDE_LANES
    if constexpr (Wide) return overlap_mask_avx2(leaf_node, query);
#endif
    return overlap_mask(leaf_node, query);
  }
  /// Node n's box (heap order: children 2n + 1, 2n + 2; root 0).
  const Box32& node(std::size_t n) const { return node_[n]; }
  int depth() const { return depth_; }
  /// The node of leaf k is first_leaf() + k; it holds slots leaf_slots(k).
  std::size_t first_leaf() const { return leaves_ - 1; }
  std::pair<std::size_t, std::size_t> leaf_slots(std::size_t leaf_node) const {
    const std::size_t b = (leaf_node - first_leaf()) * kLeaf;
    return {b, std::min(size(), b + kLeaf)};
  }

  /// Calls f(item) for every triangle whose box meets `query`.
  template <typename F>
  void for_each_overlapping(const Box32& query, F&& f) const {
    if (!empty()) visit(0, 0, query, f);
  }

 private:
  template <typename F>
  void visit(std::size_t n, int depth, const Box32& query, F& f) const {
    if (!overlap(node_[n], query)) return;
    if (depth == depth_) {
      const std::size_t first = (n - first_leaf()) * kLeaf;
      for (unsigned m = overlap_mask(n, query); m != 0; m &= m - 1) f(item_[first + std::countr_zero(m)]);
      return;
    }
    visit(2 * n + 1, depth + 1, query, f);
    visit(2 * n + 2, depth + 1, query, f);
  }

  /// The boxes of one leaf's slots, coordinate by coordinate (structure of
  /// arrays), so that overlap_mask compares them in vector registers.
  struct alignas(16) LeafBlock {
    std::int32_t lo[3][kLeaf];
    std::int32_t hi[3][kLeaf];
  };

  std::vector<std::uint32_t> item_;  ///< triangles in curve order
  std::vector<LeafBlock> block_;     ///< their boxes, kLeaf per block (empty boxes past the end)
  std::vector<Box32> node_;          ///< the tree's boxes, heap order
  std::size_t leaves_ = 1;
  int depth_ = 0;
};

inline unsigned TriangleTree::overlap_mask(std::size_t leaf_node, const Box32& q) const {
  assert(leaf_node - first_leaf() < block_.size() && query_in_range(q));
#if defined(__SSE2__)
  const LeafBlock& b = block_[leaf_node - first_leaf()];
  static_assert(kLeaf == 8, "two 4-lane vectors per coordinate");
  // A slot misses q iff on some axis lo > q.hi or q.lo > hi (signed compares).
  __m128i miss0 = _mm_setzero_si128(), miss1 = _mm_setzero_si128();
  for (int a = 0; a < 3; ++a) {
    const __m128i qlo = _mm_set1_epi32(q.lo[a]), qhi = _mm_set1_epi32(q.hi[a]);
    const auto lanes = [&](const std::int32_t* p) { return _mm_load_si128(reinterpret_cast<const __m128i*>(p)); };
    miss0 =
        _mm_or_si128(miss0, _mm_or_si128(_mm_cmpgt_epi32(lanes(b.lo[a]), qhi), _mm_cmpgt_epi32(qlo, lanes(b.hi[a]))));
    miss1 = _mm_or_si128(
        miss1, _mm_or_si128(_mm_cmpgt_epi32(lanes(b.lo[a] + 4), qhi), _mm_cmpgt_epi32(qlo, lanes(b.hi[a] + 4))));
  }
  const unsigned miss = static_cast<unsigned>(_mm_movemask_ps(_mm_castsi128_ps(miss0))) |
                        static_cast<unsigned>(_mm_movemask_ps(_mm_castsi128_ps(miss1))) << 4;
  return ~miss & 0xffu;
#else
  return overlap_mask_portable(leaf_node, q);
#endif
}

#if EMBER_WIDE_LANES
EMBER_TARGET_AVX2 inline unsigned TriangleTree::overlap_mask_avx2(std::size_t leaf_node, const Box32& q) const {
  assert(leaf_node - first_leaf() < block_.size() && query_in_range(q));
  const LeafBlock& b = block_[leaf_node - first_leaf()];
  static_assert(kLeaf == 8, "one 8-lane vector per coordinate");
  // A slot misses q iff on some axis lo > q.hi or q.lo > hi (signed compares).
  __m256i miss = _mm256_setzero_si256();
  for (int a = 0; a < 3; ++a)
    miss = _mm256_or_si256(miss, _mm256_or_si256(_mm256_cmpgt_epi32(lanes8(b.lo[a]), _mm256_set1_epi32(q.hi[a])),
                                                 _mm256_cmpgt_epi32(_mm256_set1_epi32(q.lo[a]), lanes8(b.hi[a]))));
  return ~mask8(miss) & 0xffu;
}
#endif

inline unsigned TriangleTree::overlap_mask_portable(std::size_t leaf_node, const Box32& q) const {
  assert(leaf_node - first_leaf() < block_.size() && query_in_range(q));
  const LeafBlock& b = block_[leaf_node - first_leaf()];
  unsigned mask = 0;
  for (std::size_t k = 0; k < kLeaf; ++k) {
    bool meets = true;
    for (int a = 0; a < 3; ++a) meets &= b.lo[a][k] <= q.hi[a] && q.lo[a] <= b.hi[a][k];
    mask |= static_cast<unsigned>(meets) << k;
  }
  return mask;
}

}  // namespace ember::core
