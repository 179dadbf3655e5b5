// ratio_to_double against exact rational arithmetic: the result must be the
// double nearest to num/den, ties to even, checked with mpq comparisons.
#include <gtest/gtest.h>

#include <cmath>

#include "numbers/ratio.hpp"
#include "support/numbers_oracle.hpp"
#include "support/correct_rounding.hpp"

namespace ember::test {
namespace {

/// True iff d is num/den rounded to nearest, ties to even (exact, via mpq).
::testing::AssertionResult correctly_rounded(const mpz_class& num, const mpz_class& den, double d) {
  mpq_class q(num, den);
  q.canonicalize();  // mpq_class(num, den) keeps a negative or non-reduced denominator as given
  return rounds_correctly(q, d) << " (" << num << " / " << den << ")";
}

template <int A, int B>
::testing::AssertionResult check(const mpz_class& num, const mpz_class& den) {
  return correctly_rounded(num, den, ratio_to_double(from_mpz<A>(num), from_mpz<B>(den)));
}

template <int A, int B>
void random_ratios(std::uint64_t seed, int count) {
  std::mt19937_64 rng(seed);
  for (int i = 0; i < count; ++i) {
    const mpz_class num = random_value(rng, A);
    mpz_class den = random_value(rng, B);
    if (den == 0) den = 1;
    ASSERT_TRUE((check<A, B>(num, den))) << "Int<" << A << "> / Int<" << B << ">";
  }
}

TEST(RatioToDouble, RandomAllWidths) {
  random_ratios<188, 162>(1, 30000);  // exported SSS points
  random_ratios<189, 162>(2, 10000);
  random_ratios<161, 134>(3, 10000);
  random_ratios<84, 55>(4, 10000);
  random_ratios<27, 1>(5, 5000);  // integer points
  random_ratios<53, 53>(6, 10000);
  random_ratios<64, 64>(7, 10000);
  random_ratios<127, 127>(8, 10000);
  random_ratios<255, 255>(9, 10000);
  random_ratios<1, 255>(10, 2000);
  random_ratios<255, 1>(11, 2000);
  random_ratios<26, 255>(12, 5000);
  random_ratios<255, 26>(13, 5000);
}

TEST(RatioToDouble, SmallExhaustive) {
  for (int n = -300; n <= 300; ++n)
    for (int d = -300; d <= 300; ++d) {
      if (d == 0) continue;
      ASSERT_TRUE((check<9, 9>(n, d)));
    }
}

/// num = m·den·2^k (±delta) for odd 54-bit m: exactly halfway between two doubles.
template <int A, int B>
void halfway_cases(std::uint64_t seed, int count) {
  std::mt19937_64 rng(seed);
  int tested = 0;
  for (int i = 0; i < count; ++i) {
    const mpz_class m = pow2(53) + 2 * mpz_class(from_u64(rng() >> 12)) + 1;  // odd, 54 bits
    const int den_len = 1 + static_cast<int>(rng() % std::min(B, A - 54));
    const mpz_class den = abs(random_with_length(rng, den_len));
    const int room = A - 54 - den_len;  // m·den < 2^(54+den_len)
    const int k = static_cast<int>(rng() % (room + 1));
    for (int sign_n : {1, -1})
      for (int sign_d : {1, -1}) {
        const mpz_class exact = m * den << k;
        for (long delta : {0L, 1L, -1L, 2L, -2L}) {
          const mpz_class num = sign_n * (exact + delta);
          if (abs(num) >= pow2(A)) continue;
          ASSERT_TRUE((check<A, B>(num, sign_d * den))) << "delta " << delta;
          ++tested;
        }
        // Halfway as a quotient by a power of two: m / 2^j.
        const int j = static_cast<int>(rng() % (B - 1));
        ASSERT_TRUE((check<A, B>(sign_n * m, sign_d * pow2(j))));
        ++tested;
      }
  }
  EXPECT_GE(tested, count * 4);
}

TEST(RatioToDouble, ExactHalfwayAndNeighbours) {
  halfway_cases<188, 162>(21, 4000);
  halfway_cases<255, 255>(22, 2000);
  halfway_cases<127, 64>(23, 2000);
  halfway_cases<80, 20>(24, 2000);
}

TEST(RatioToDouble, NearHalfwayWithLongDenominators) {
  // The fast path truncates den to 64 bits: put the quotient within a tiny
  // distance of a midpoint while den has far more bits, so only the exact
  // comparison can decide.
  std::mt19937_64 rng(31);
  for (int i = 0; i < 5000; ++i) {
    const mpz_class den = abs(random_with_length(rng, 100 + static_cast<int>(rng() % 60)));
    const mpz_class m = pow2(53) + 2 * mpz_class(from_u64(rng() >> 12)) + 1;
    const mpz_class half_den = den / 2;
    for (const mpz_class& offset : {mpz_class(0), mpz_class(1), mpz_class(-1), half_den, mpz_class(-half_den),
                                    mpz_class(den - 1), mpz_class(1 - den)}) {
      // (m·den + offset) / (2·den) = m/2 + offset/(2·den): within 2^-100-ish of a midpoint.
      const mpz_class num = m * den + offset;
      ASSERT_TRUE((check<215, 162>(num, 2 * den)));
      ASSERT_TRUE((check<215, 162>(-num, 2 * den)));
    }
  }
}

TEST(RatioToDouble, ExactlyRepresentable) {
  std::mt19937_64 rng(41);
  for (int i = 0; i < 5000; ++i) {
    const mpz_class mant = mpz_class(from_u64(rng() >> 11));  // up to 53 bits
    const mpz_class den = random_value(rng, 100);
    if (den == 0 || mant == 0) continue;
    const double d = ratio_to_double(from_mpz<160>(mant * den), from_mpz<100>(den));
    ASSERT_EQ(mpq_class(d), mpq_class(mant)) << mant << " * " << den;
  }
}

TEST(RatioToDouble, ExtremeMagnitudes) {
  const mpz_class max255 = pow2(255) - 1;
  for (int s : {1, -1}) {
    EXPECT_TRUE((check<255, 255>(s * max255, 1)));
    EXPECT_TRUE((check<255, 255>(s, max255)));
    EXPECT_TRUE((check<255, 255>(s * max255, max255)));
    EXPECT_TRUE((check<255, 255>(s * max255, max255 - 1)));
    EXPECT_TRUE((check<255, 255>(s * pow2(254), 3)));
    EXPECT_TRUE((check<255, 255>(s, pow2(254))));
    EXPECT_TRUE((check<255, 255>(s * 3, pow2(254) + 1)));
    EXPECT_TRUE((check<255, 255>(s * (pow2(254) + 1), -1)));
  }
  // 2^-254 and 2^254 are exact and normal.
  EXPECT_EQ(ratio_to_double(Int<255>(1), from_mpz<255>(pow2(254))), std::ldexp(1.0, -254));
  EXPECT_EQ(ratio_to_double(from_mpz<255>(-pow2(254)), Int<2>(1)), -std::ldexp(1.0, 254));
  // Zero numerator: +0 regardless of the denominator's sign.
  EXPECT_FALSE(std::signbit(ratio_to_double(Int<188>(0), Int<162>(-5))));
  // All-ones numerators round up into the next binade (mantissa carry).
  for (int bits : {54, 60, 64, 65, 100, 128, 129, 200}) EXPECT_TRUE((check<255, 64>(pow2(bits) - 1, 1))) << bits;
  for (int bits : {54, 60, 64, 65, 100, 128, 129, 200}) EXPECT_TRUE((check<255, 64>(pow2(bits) - 1, 3))) << bits;
}

}  // namespace
}  // namespace ember::test
