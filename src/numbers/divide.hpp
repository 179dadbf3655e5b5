#pragma once
// floor(num * 2^shift / den) by binary long division. Only for rare fallback
// paths (finding a point inside a sliver polygon): it costs ~bitlen(num)
// limb-array steps, so it must never appear on a hot path.
#include <array>
#include <cassert>
#include <cstdint>

#include "numbers/int.hpp"

namespace ember {

/// floor(num * 2^shift / den) for den != 0, 0 <= shift <= 64. The caller
/// guarantees |quotient| < 2^126 (checked in debug builds).
template <int A, int B>
__int128 floor_scaled_ratio(const Int<A>& num, const Int<B>& den, int shift) {
  assert(!den.is_zero() && shift >= 0 && shift <= 64);
  constexpr int LN = Int<A>::limbs + 1, LD = Int<B>::limbs + 1;
  using u64 = std::uint64_t;
  // Magnitudes: n = |num| << shift (one spare limb), d = |den|.
  std::array<u64, LN> n{};
  std::array<u64, LD> d{};
  const Int<A> an = num.abs();
  const Int<B> ad = den.abs();
  for (int i = 0; i < Int<A>::limbs; ++i) n[i] = an.limb(i);
  for (int i = 0; i < Int<B>::limbs; ++i) d[i] = ad.limb(i);
  if (shift > 0) {
    const int words = shift / 64, bits = shift % 64;
    for (int i = LN - 1; i >= 0; --i) {
      const int src = i - words;
      u64 v = src >= 0 ? n[src] << bits : 0;
      if (bits && src - 1 >= 0) v |= n[src - 1] >> (64 - bits);
      n[i] = v;
    }
  }
  // Remainder r < d always fits LD limbs (d has a spare top limb).
  std::array<u64, LD> r{};
  unsigned __int128 q = 0;
  for (int bit = 64 * LN - 1; bit >= 0; --bit) {
    // r = 2r + next bit of n
    for (int i = LD - 1; i > 0; --i) r[i] = (r[i] << 1) | (r[i - 1] >> 63);
    r[0] = (r[0] << 1) | ((n[bit / 64] >> (bit % 64)) & 1);
    // r >= d ?
    bool ge = true;
    for (int i = LD - 1; i >= 0; --i)
      if (r[i] != d[i]) {
        ge = r[i] > d[i];
        break;
      }
    if (ge) {
      u64 borrow = 0;
      for (int i = 0; i < LD; ++i) {
        const u64 di = d[i] + borrow;
        const u64 next = (di < borrow) || (r[i] < di) ? 1 : 0;
        r[i] -= di;
        borrow = next;
      }
      assert(bit < 126);
      q |= static_cast<unsigned __int128>(1) << bit;
    }
  }
  bool rem = false;
  for (const u64 x : r) rem |= x != 0;
  const bool negative = num.negative() != den.negative() && !num.is_zero();
  const __int128 mag = static_cast<__int128>(q);
  return negative ? -mag - (rem ? 1 : 0) : mag;
}

}  // namespace ember
