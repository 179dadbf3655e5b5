#pragma once
// Exact conversions between Int<Bits> and GMP integers that use only the
// two's-complement limbs (never Int's own arithmetic): the shared basis of the
// numbers and geometry oracle tests.
#include <gmpxx.h>

#include <array>
#include <cstdint>

#include "numbers/int.hpp"

namespace ember::test {

inline mpz_class from_u64(std::uint64_t x) {
  mpz_class r;
  mpz_import(r.get_mpz_t(), 1, -1, sizeof x, 0, 0, &x);
  return r;
}

inline mpz_class pow2(int k) {
  mpz_class r = 1;
  r <<= k;
  return r;
}

/// Value of an Int read only through its two's-complement limbs.
template <int B>
mpz_class to_mpz(const Int<B>& x) {
  constexpr int L = Int<B>::limbs;
  mpz_class r = 0;
  for (int i = L - 1; i >= 0; --i) {
    r <<= 64;
    r += from_u64(x.limb(i));
  }
  if (x.negative()) r -= pow2(64 * L);
  return r;
}

/// Int holding v (the caller guarantees |v| < 2^B), built only through from_limbs.
template <int B>
Int<B> from_mpz(const mpz_class& v) {
  constexpr int L = Int<B>::limbs;
  mpz_class m = v;
  if (m < 0) m += pow2(64 * L);
  std::array<std::uint64_t, L> limbs{};
  for (int i = 0; i < L; ++i) {
    mpz_class part = m >> (64 * i);
    std::uint64_t w = 0;
    std::size_t count = 0;
    mpz_class low = part & mpz_class(from_u64(~std::uint64_t{0}));
    mpz_export(&w, &count, -1, sizeof w, 0, 0, low.get_mpz_t());
    limbs[i] = count ? w : 0;
  }
  return Int<B>::from_limbs(limbs);
}

}  // namespace ember::test
