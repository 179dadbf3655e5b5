#pragma once
// Per-triangle extents along D directions (solid_proof.hpp's
// ProjectedExtent), stored in each leaf of a TriangleTree like the leaf's
// boxes (direction by direction), so that the broad phases' leaf pairs
// dismiss the slots apart from a triangle eight at a time instead of
// comparing extents pair by pair. The directions are the caller's:
// LeafDiagonals (the four diagonals, exact) and LeafFrameExtents (a principal
// frame, widened past its rounding).
#if defined(__SSE2__)
#include <emmintrin.h>
#endif

#include <cstdint>
#include <limits>
#include <vector>

#include "core/support/fill_vector.hpp"
#include "core/search/extents.hpp"
#include "core/search/triangle_tree.hpp"
#include "core/support/wide_lanes.hpp"

namespace ember::core {

template <std::size_t D>
class LeafExtents {
 public:
  using Extent = ProjectedExtent<D>;

  /// The extent of the triangle in tree slot `slot`.
  Extent extent(std::size_t slot) const {
    const Block& b = block_[slot / TriangleTree::kLeaf];
    const std::size_t s = slot % TriangleTree::kLeaf;
    Extent e;
    for (std::size_t d = 0; d < D; ++d) {
      e.lo[d] = b.lo[d][s];
      e.hi[d] = b.hi[d][s];
    }
    return e;
  }

  /// Bit k set iff slot k of the leaf is apart from a triangle with extent
  /// `e` (extents_apart).
  unsigned apart_mask(std::size_t leaf_node, const Extent& e) const {
#if defined(__SSE2__)
    const Block& b = block_[leaf_node - first_leaf_];
    static_assert(TriangleTree::kLeaf == 8, "two 4-lane vectors per direction");
    __m128i apart0 = _mm_setzero_si128(), apart1 = _mm_setzero_si128();
    for (std::size_t d = 0; d < D; ++d) {
      const __m128i lo = _mm_set1_epi32(static_cast<std::int32_t>(e.lo[d]));
      const __m128i hi = _mm_set1_epi32(static_cast<std::int32_t>(e.hi[d]));
      const auto at = [](const std::int32_t* p) { return _mm_load_si128(reinterpret_cast<const __m128i*>(p)); };
      apart0 = _mm_or_si128(apart0, _mm_or_si128(_mm_cmpgt_epi32(at(b.lo[d]), hi), _mm_cmpgt_epi32(lo, at(b.hi[d]))));
      apart1 = _mm_or_si128(apart1,
                            _mm_or_si128(_mm_cmpgt_epi32(at(b.lo[d] + 4), hi), _mm_cmpgt_epi32(lo, at(b.hi[d] + 4))));
    }
    return static_cast<unsigned>(_mm_movemask_ps(_mm_castsi128_ps(apart0))) |
           static_cast<unsigned>(_mm_movemask_ps(_mm_castsi128_ps(apart1))) << 4;
#else
    return apart_mask_portable(leaf_node, e);
#endif
  }

#if EMBER_WIDE_LANES
  /// The same in eight lanes at once (wide_lanes.hpp): only where cpu_has_avx2().
  EMBER_TARGET_AVX2 unsigned apart_mask_avx2(std::size_t leaf_node, const Extent& e) const {
    const Block& b = block_[leaf_node - first_leaf_];
    __m256i apart = _mm256_setzero_si256();
    for (std::size_t d = 0; d < D; ++d) {
      const __m256i lo = _mm256_set1_epi32(static_cast<std::int32_t>(e.lo[d]));
      const __m256i hi = _mm256_set1_epi32(static_cast<std::int32_t>(e.hi[d]));
      apart = _mm256_or_si256(
          apart, _mm256_or_si256(_mm256_cmpgt_epi32(lanes8(b.lo[d]), hi), _mm256_cmpgt_epi32(lo, lanes8(b.hi[d]))));
    }
    return mask8(apart);
  }
#endif

  /// apart_mask, in eight lanes when Wide (only where cpu_has_avx2()).
  template <bool Wide>
  [[gnu::always_inline]] unsigned apart_mask_in(std::size_t leaf_node, const Extent& e) const {
#if EMBER_WIDE_LANES
    if constexpr (Wide) return apart_mask_avx2(leaf_node, e);
#endif
    return apart_mask(leaf_node, e);
  }

  /// The same without vector instructions (what apart_mask is where SSE2 is missing).
  unsigned apart_mask_portable(std::size_t leaf_node, const Extent& e) const {
    const Block& b = block_[leaf_node - first_leaf_];
    unsigned mask = 0;
    for (std::size_t k = 0; k < TriangleTree::kLeaf; ++k) {
      bool apart = false;
      for (std::size_t d = 0; d < D; ++d) apart |= b.lo[d][k] > e.hi[d] || e.lo[d] > b.hi[d][k];
      mask |= static_cast<unsigned>(apart) << k;
    }
    return mask;
  }

 protected:
  LeafExtents() = default;  ///< no leaves (filled by assignment)
  /// Stores extent_of(item) for every triangle of the tree; each bound must
  /// fit int32.
  template <typename ExtentOf>
  void fill(const TriangleTree& tree, ExtentOf&& extent_of) {
    first_leaf_ = tree.first_leaf();
    tree.fill_leaf_blocks(block_, [&](Block& b, std::size_t s, std::uint32_t item) {
      // Empty slots: an extent apart from everything (never a candidate anyway).
      Extent e{};
      e.lo.fill(std::numeric_limits<std::int32_t>::max());
      e.hi.fill(std::numeric_limits<std::int32_t>::min());
      if (item != TriangleTree::kNoItem) e = extent_of(item);
      for (std::size_t d = 0; d < D; ++d) {
        b.lo[d][s] = static_cast<std::int32_t>(e.lo[d]);
        b.hi[d][s] = static_cast<std::int32_t>(e.hi[d]);
      }
    });
  }

 private:
  struct alignas(16) Block {
    std::int32_t lo[D][TriangleTree::kLeaf], hi[D][TriangleTree::kLeaf];
  };
  std::size_t first_leaf_ = 0;
  FillVector<Block> block_;  ///< every slot written by fill
};

}  // namespace ember::core
