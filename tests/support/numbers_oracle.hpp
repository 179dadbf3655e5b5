#pragma once
// GMP oracle for Int<Bits>: conversions that do not use Int's own arithmetic,
// plus deterministic generators of random and boundary values.
#include <gmpxx.h>

#include <cstdint>
#include <random>
#include <vector>

#include "numbers/int.hpp"
#include "support/int_gmp.hpp"

namespace ember::test {

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
    mpz_class v = random_with_length(rng, bits);       // random bits below bit `bits`
    v = abs(v) - pow2(bits - 1);                       // [0, 2^(bits-1)) ...
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
