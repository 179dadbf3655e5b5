#pragma once
// GMP oracle for Int<Bits>: conversions that do not use Int's own arithmetic,
// plus deterministic generators of random and boundary values.
#include <gmpxx.h>

#include <cstdint>
#include <random>
#include <vector>

#include "ember/numbers/int.hpp"

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

/// Uniform value of exactly `len` bits (len = 0 gives 0), random sign.
inline mpz_class random_with_length(std::mt19937_64& rng, int len) {
  if (len == 0) return 0;
  mpz_class v = 0;
  for (int done = 0; done < len; done += 64) {
    v <<= 64;
    v += from_u64(rng());
  }
  v >>= ((len + 63) / 64) * 64 - len;  // keep exactly len random bits
  v |= pow2(len - 1);                  // force the top bit
  return (rng() & 1) ? mpz_class(-v) : v;
}

/// Random value with |v| < 2^bits: half the time uniform over the full range,
/// half the time with a uniformly chosen bit length (so small values appear).
inline mpz_class random_value(std::mt19937_64& rng, int bits) {
  if (rng() & 1) {
    mpz_class v = random_with_length(rng, bits);  // random bits below bit `bits`
    v = abs(v) - pow2(bits - 1);                  // [0, 2^(bits-1)) ...
    v += (rng() & 1) ? pow2(bits - 1) : mpz_class(0);  // ... or the upper half
    return (rng() & 1) ? mpz_class(-v) : v;
  }
  return random_with_length(rng, static_cast<int>(rng() % (bits + 1)));
}

/// 0, ±1, ±(2^(k-1)±1), ±2^(k-1), ±(2^k-1) and limb edges 2^(64j)±1 below 2^k.
inline std::vector<mpz_class> boundary_values(int k) {
  std::vector<mpz_class> pos = {1, pow2(k) - 1, pow2(k - 1)};
  if (k >= 2) pos.push_back(pow2(k - 1) + 1);
  if (k >= 2) pos.push_back(pow2(k - 1) - 1);
  if (k >= 3) pos.push_back(pow2(k) - 2);
  for (int j = 63; j < k; j += 64) {  // two's-complement limb sign bits and limb carries
    for (int t : {j, j + 1}) {
      if (t >= k) continue;
      pos.push_back(pow2(t));
      pos.push_back(pow2(t) - 1);
      pos.push_back(pow2(t) + 1);
    }
  }
  std::vector<mpz_class> out = {0};
  for (const auto& p : pos) {
    out.push_back(p);
    out.push_back(-p);
  }
  return out;
}

}  // namespace ember::test
