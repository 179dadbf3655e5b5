#pragma once
// The vertex ids of the triangles in each leaf of a TriangleTree, stored
// like the leaf's boxes (coordinate by coordinate), so that the solid
// proof's leaf pairs find a triangle's neighbours among eight slots at once
// (contact_search.cpp).
#if defined(__SSE2__)
#include <emmintrin.h>
#endif

#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "core/support/fill_vector.hpp"
#include "core/search/contact_triangle.hpp"
#include "core/search/triangle_tree.hpp"

namespace ember::core {

/// The vertex ids of the triangles in each tree leaf, coordinate by
/// coordinate like the leaf's boxes, to find a triangle's neighbours in a
/// leaf eight at a time. Empty slots hold an id no vertex has.
class LeafVertexIds {
 public:
  LeafVertexIds(const TriangleTree& tree, std::span<const ContactTriangle> tris) : first_leaf_(tree.first_leaf()) {
    tree.fill_leaf_blocks(block_, [&](Block& b, std::size_t s, std::uint32_t item) {
      for (int c = 0; c < 3; ++c) b.id[c][s] = item != TriangleTree::kNoItem ? tris[item].id[c] : kNoVertex;
    });
  }

  /// Per slot of the leaf, whether its triangle shares vertices with a
  /// triangle whose vertex ids are `ids`: `neighbours` bit k set iff slot k
  /// shares one or two (three shared: the same triangle), `sharing` iff it
  /// shares any.
  struct Masks {
    unsigned neighbours = 0, sharing = 0;
    bool operator==(const Masks&) const = default;
  };

  Masks shared_masks(std::size_t leaf_node, const std::array<std::uint32_t, 3>& ids) const {
#if defined(__SSE2__)
    const Block& b = block_[leaf_node - first_leaf_];
    static_assert(TriangleTree::kLeaf == 8, "two 4-lane vectors per corner");
    // Per slot minus the number of shared vertices: each match adds -1.
    __m128i count0 = _mm_setzero_si128(), count1 = _mm_setzero_si128();
    for (int c = 0; c < 3; ++c) {
      const __m128i lo = _mm_load_si128(reinterpret_cast<const __m128i*>(b.id[c]));
      const __m128i hi = _mm_load_si128(reinterpret_cast<const __m128i*>(b.id[c] + 4));
      for (const std::uint32_t v : ids) {
        const __m128i vv = _mm_set1_epi32(static_cast<int>(v));
        count0 = _mm_add_epi32(count0, _mm_cmpeq_epi32(lo, vv));
        count1 = _mm_add_epi32(count1, _mm_cmpeq_epi32(hi, vv));
      }
    }
    const auto one_or_two = [](__m128i count) {
      const __m128i m =
          _mm_or_si128(_mm_cmpeq_epi32(count, _mm_set1_epi32(-1)), _mm_cmpeq_epi32(count, _mm_set1_epi32(-2)));
      return static_cast<unsigned>(_mm_movemask_ps(_mm_castsi128_ps(m)));
    };
    const auto any = [](__m128i count) {
      const __m128i none = _mm_cmpeq_epi32(count, _mm_setzero_si128());
      return ~static_cast<unsigned>(_mm_movemask_ps(_mm_castsi128_ps(none))) & 0xfu;
    };
    return {one_or_two(count0) | one_or_two(count1) << 4, any(count0) | any(count1) << 4};
#else
    return shared_masks_portable(leaf_node, ids);
#endif
  }

#if EMBER_WIDE_LANES
  /// The same in eight lanes at once (wide_lanes.hpp): only where cpu_has_avx2().
  EMBER_TARGET_AVX2 Masks shared_masks_avx2(std::size_t leaf_node, const std::array<std::uint32_t, 3>& ids) const {
    const Block& b = block_[leaf_node - first_leaf_];
    // Per slot minus the number of shared vertices: each match adds -1.
    __m256i count = _mm256_setzero_si256();
    for (int c = 0; c < 3; ++c) {
      const __m256i slot = lanes8(b.id[c]);
      for (const std::uint32_t v : ids)
        count = _mm256_add_epi32(count, _mm256_cmpeq_epi32(slot, _mm256_set1_epi32(static_cast<int>(v))));
    }
    const unsigned one_or_two = mask8(_mm256_or_si256(_mm256_cmpeq_epi32(count, _mm256_set1_epi32(-1)),
                                                      _mm256_cmpeq_epi32(count, _mm256_set1_epi32(-2))));
    const unsigned any = ~mask8(_mm256_cmpeq_epi32(count, _mm256_setzero_si256())) & 0xffu;
    return {one_or_two, any};
  }
#endif

  /// shared_masks, in eight lanes when Wide (only where cpu_has_avx2()).
  template <bool Wide>
  [[gnu::always_inline]] Masks shared_masks_in(std::size_t leaf_node, const std::array<std::uint32_t, 3>& ids) const {
#if EMBER_WIDE_LANES
    if constexpr (Wide) return shared_masks_avx2(leaf_node, ids);
#endif
    return shared_masks(leaf_node, ids);
  }

  /// The same without vector instructions (what shared_masks is where SSE2 is missing).
  Masks shared_masks_portable(std::size_t leaf_node, const std::array<std::uint32_t, 3>& ids) const {
    const Block& b = block_[leaf_node - first_leaf_];
    Masks masks;
    for (std::size_t k = 0; k < TriangleTree::kLeaf; ++k) {
      int shared = 0;
      for (int c = 0; c < 3; ++c)
        for (const std::uint32_t v : ids) shared += b.id[c][k] == v;
      masks.neighbours |= static_cast<unsigned>(shared == 1 || shared == 2) << k;
      masks.sharing |= static_cast<unsigned>(shared > 0) << k;
    }
    return masks;
  }

 private:
  static constexpr std::uint32_t kNoVertex = UINT32_MAX;
  struct alignas(16) Block {
    std::uint32_t id[3][TriangleTree::kLeaf];
  };
  std::size_t first_leaf_;
  FillVector<Block> block_;  ///< every slot written by fill_leaf_blocks
};

}  // namespace ember::core
