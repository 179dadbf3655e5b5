#pragma once
// Correctly rounded conversion of an exact ratio num/den to double.
//
// Used to export homogeneous points (x_i / x4). The result is num/den rounded
// to nearest, ties to even, for any signs and any Int widths. No GMP, no heap.
//
// Range: |num| < 2^255 and 1 <= |den| < 2^255, so 2^-255 < |num/den| < 2^255
// whenever num != 0: the result is always a normal double (2^-1022 .. 2^1024),
// never inf, never subnormal, so no overflow/underflow handling is needed.
//
// Algorithm (magnitudes n = |num|, d = |den|, bit lengths ln, ld):
//  1. If n, d < 2^53 both convert to double exactly and IEEE division is
//     already correctly rounded (covers integer points, where x4 = ±1).
//  2. Otherwise take n' = floor(n·2^(127-ln)) in [2^126, 2^127) and
//     d' = floor(d·2^(64-ld)) in [2^63, 2^64), and q = floor(n'/d') (one
//     128/64 division; q < 2^64 because n' < 2^127 <= 2^63·d'). With
//     Qs = n·2^(127-ln) / (d·2^(64-ld)) = (n'+en)/(d'+ed), en, ed in [0,1):
//       Qs <= (n'+1)/d' < q + 1 + 2^-63
//       Qs >= n'/(d'+1) = n'/d' - n'/(d'(d'+1)) > q - 2^127/2^126 = q - 2
//     so Qs is in (q-2, q+2). q has 63 or 64 bits; the double keeps 53, so
//     sh = bitlen(q) - 53 >= 10 bits are rounded away, the rounding midpoint
//     in units of q is at r = q mod 2^sh == 2^(sh-1) and the nearest other
//     midpoints are 2^sh >= 1024 units away. Rounding q gives the rounding of
//     Qs unless that midpoint lies in (q-2, q+2), i.e. |r - 2^(sh-1)| < 2; we
//     fall back whenever |r - 2^(sh-1)| <= 4 (probability ~2^-7 on random data).
//  3. Fallback: the exact value of the one candidate midpoint M = m·2^E
//     (m odd, 54 bits) decides: compare n with m·d·2^E by exact multi-limb
//     multiplication and shifts (no division), ties go to the even mantissa.
#include <array>
#include <bit>
#include <cstdint>
#include <cstring>

#include "numbers/int.hpp"

namespace ember {

namespace detail::ratio {

using u64 = std::uint64_t;

/// Bit length of a magnitude stored in L limbs (0 for zero).
template <std::size_t L>
inline int bit_length(const std::array<u64, L>& a) {
  for (int i = static_cast<int>(L) - 1; i >= 0; --i)
    if (a[i] != 0) return 64 * i + 64 - std::countl_zero(a[i]);
  return 0;
}

/// Limb i of a magnitude, zero outside [0, L).
template <std::size_t L>
inline u64 limb_or_zero(const std::array<u64, L>& a, int i) {
  return (i >= 0 && i < static_cast<int>(L)) ? a[i] : 0;
}

/// floor(a / 2^pos) mod 2^64, pos may be negative (shifts left, zero fill).
template <std::size_t L>
inline u64 window64(const std::array<u64, L>& a, int pos) {
  // floor division so that pos = 64k + s with 0 <= s < 64 also for pos < 0.
  const int k = pos >= 0 ? pos / 64 : -((-pos + 63) / 64);
  const int s = pos - 64 * k;
  const u64 lo = limb_or_zero(a, k), hi = limb_or_zero(a, k + 1);
  return s == 0 ? lo : (lo >> s) | (hi << (64 - s));
}

/// q = floor(hi:lo / d) for hi < d (so q fits 64 bits).
inline u64 div128by64(u64 hi, u64 lo, u64 d) {
#if defined(__x86_64__)
  u64 q, r;
  __asm__("divq %4" : "=a"(q), "=d"(r) : "a"(lo), "d"(hi), "rm"(d));
  return q;
#else
  return static_cast<u64>(((static_cast<u128>(hi) << 64) | lo) / d);
#endif
}

/// x · 2^shift into K limbs (the caller sized K so nothing is lost).
template <std::size_t K, std::size_t L>
inline std::array<u64, K> shifted(const std::array<u64, L>& x, int shift) {
  std::array<u64, K> out{};
  for (int i = 0; i < static_cast<int>(K); ++i) out[i] = window64(x, 64 * i - shift);
  return out;
}

/// Compares n with m·d·2^E exactly; returns -1, 0, +1. K limbs hold both sides.
template <std::size_t K, std::size_t LN, std::size_t LD>
inline int compare_with_midpoint(const std::array<u64, LN>& n, const std::array<u64, LD>& d, u64 m, int e) {
  std::array<u64, LD + 1> md{};
  u64 carry = 0;
  for (std::size_t i = 0; i < LD; ++i) {
    const u128 t = static_cast<u128>(d[i]) * m + carry;
    md[i] = static_cast<u64>(t);
    carry = static_cast<u64>(t >> 64);
  }
  md[LD] = carry;
  const auto lhs = shifted<K>(n, e < 0 ? -e : 0);
  const auto rhs = shifted<K>(md, e > 0 ? e : 0);
  for (int i = static_cast<int>(K) - 1; i >= 0; --i)
    if (lhs[i] != rhs[i]) return lhs[i] < rhs[i] ? -1 : 1;
  return 0;
}

/// Double with mantissa mant in [2^52, 2^53] and value mant·2^scale (normal range).
inline double compose(u64 mant, int scale, bool negative) {
  if (mant == (u64{1} << 53)) {  // rounding carried into the next binade
    mant >>= 1;
    ++scale;
  }
  const int biased = scale + 52 + 1023;
  const u64 bits = (negative ? u64{1} << 63 : 0) | (static_cast<u64>(biased) << 52) | (mant & ((u64{1} << 52) - 1));
  double r;
  std::memcpy(&r, &bits, sizeof r);
  return r;
}

}  // namespace detail::ratio

/// num/den rounded to the nearest double, ties to even. Requires den != 0.
/// A zero numerator gives +0.0 (never -0.0, which would leak into exported files).
template <int A, int B>
double ratio_to_double(const Int<A>& num, const Int<B>& den) {
  using namespace detail::ratio;
  constexpr std::size_t LN = detail::mag_limbs(A), LD = detail::mag_limbs(B);
  assert(!den.is_zero());
  const bool negative = num.negative() != den.negative();
  const auto n = detail::magnitude<LN>(num);
  const auto d = detail::magnitude<LD>(den);
  const int ln = bit_length(n), ld = bit_length(d);
  if (ln == 0) return 0.0;

  // 1. Both exact in double: IEEE division rounds correctly.
  if (ln <= 53 && ld <= 53) {
    const double q = static_cast<double>(n[0]) / static_cast<double>(d[0]);
    return negative ? -q : q;
  }

  // 2. One 128/64 division of the leading bits (error bound in the header).
  const int npos = ln - 127;  // n' = floor(n / 2^npos), top bit at 126
  const u64 nhi = window64(n, npos + 64), nlo = window64(n, npos);
  const u64 dtop = window64(d, ld - 64);  // d' = floor(d / 2^(ld-64)), top bit at 63
  const u64 q = div128by64(nhi, nlo, dtop);
  const int sh = 64 - std::countl_zero(q) - 53;  // 10 or 11
  const u64 half = u64{1} << (sh - 1);
  const u64 r = q & ((u64{1} << sh) - 1);
  const u64 lower = q >> sh;
  // value = Qs · 2^(ln-127-(ld-64)); the mantissa unit is 2^sh of that.
  const int scale = sh + ln - ld - 63;
  const u64 dist = r > half ? r - half : half - r;
  if (dist > 4) return compose(lower + (r > half ? 1 : 0), scale, negative);

  // 3. Exact decision against the midpoint M = (2·lower+1) · 2^(scale-1).
  //    E = scale-1 = sh+ln-ld-64 lies in [10+1-B-64, 11+A-1-64] = [-53-B, A-54], so the
  //    left side n·2^max(0,-E) has at most A+B+53 bits and the right side
  //    m·d·2^max(0,E) (m < 2^54) at most 54+B+A-54 = A+B bits.
  constexpr std::size_t K = static_cast<std::size_t>((A + B + 54 + 63) / 64);
  static_assert(K <= 9, "255 + 255 + 54 = 564 bits fit 9 limbs");
  const int c = compare_with_midpoint<K>(n, d, 2 * lower + 1, scale - 1);
  const bool up = c > 0 || (c == 0 && (lower & 1) != 0);
  return compose(lower + (up ? 1 : 0), scale, negative);
}

}  // namespace ember
