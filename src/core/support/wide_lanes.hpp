#pragma once
// Eight-lane (AVX2) versions of the leaf tests, chosen at run time.
//
// The broad phases (contact_search.cpp, solid_route.cpp) spend most of their
// instructions comparing one box, vertex-id triple or diagonal extent with
// the eight slots of a leaf (TriangleTree::overlap_mask,
// LeafVertexIds::shared_masks, LeafDiagonals::apart_mask). With SSE2 that
// is two 4-lane halves per coordinate; AVX2 compares all eight at once.
// The library is built for the baseline x86-64 (SSE2), so the 8-lane code
// is compiled per function (the target attribute) and taken only where the
// processor reports AVX2 (cpu_has_avx2); elsewhere the 4-lane code runs.
// Both give the same masks (tests/core/*_test.cpp compare them with the
// portable loops), so the choice never changes a result.
#if (defined(__GNUC__) || defined(__clang__)) && (defined(__x86_64__) || defined(__i386__))
#include <immintrin.h>
#define EMBER_WIDE_LANES 1
#define EMBER_TARGET_AVX2 __attribute__((target("avx2")))
#else
#define EMBER_WIDE_LANES 0
#define EMBER_TARGET_AVX2
#endif

namespace ember::core {

/// Whether this processor runs the 8-lane leaf tests.
inline bool cpu_has_avx2() {
#if EMBER_WIDE_LANES
  return __builtin_cpu_supports("avx2");
#else
  return false;
#endif
}

#if EMBER_WIDE_LANES
/// Eight 32-bit lanes from p (no alignment needed).
EMBER_TARGET_AVX2 inline __m256i lanes8(const void* p) { return _mm256_loadu_si256(static_cast<const __m256i*>(p)); }
/// Bit k set iff lane k of m is all ones.
EMBER_TARGET_AVX2 inline unsigned mask8(__m256i m) {
  return static_cast<unsigned>(_mm256_movemask_ps(_mm256_castsi256_ps(m)));
}
#endif

}  // namespace ember::core
