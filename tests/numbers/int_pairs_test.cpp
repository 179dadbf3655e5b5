// Oracle tests of Int binary operations (+, -, *, comparisons) against GMP for
// the width pairs the geometry uses: boundary values crossed with boundary
// values, plus random values in all four sign combinations.
#include <gtest/gtest.h>

#include <algorithm>

#include "support/numbers_oracle.hpp"

namespace ember::test {
namespace {

/// Number of random pairs per width pair (each tested in 4 sign combinations).
constexpr int kRandomPairs = 1500;

struct Tally {
  long checks = 0;
  int failures = 0;
};

template <int A, int B>
void check_ops(const mpz_class& ma, const mpz_class& mb, Tally& t) {
  const Int<A> a = from_mpz<A>(ma);
  const Int<B> b = from_mpz<B>(mb);
  auto expect = [&](const char* op, const mpz_class& got, const mpz_class& want) {
    ++t.checks;
    if (got != want && t.failures++ < 5)
      ADD_FAILURE() << "Int<" << A << "> " << op << " Int<" << B << ">: a=" << ma << " b=" << mb << " got " << got
                    << " want " << want;
  };
  if constexpr (std::max(A, B) + 1 <= kMaxBits) {
    const auto s = a + b;
    const auto d = a - b;
    static_assert(decltype(s)::bits == std::max(A, B) + 1 && decltype(d)::bits == std::max(A, B) + 1);
    expect("+", to_mpz(s), ma + mb);
    expect("-", to_mpz(d), ma - mb);
    expect("+ fits", mpz_class(s.fits_bound() && d.fits_bound()), 1);
  }
  if constexpr (A + B <= kMaxBits) {
    const auto p = a * b;
    static_assert(decltype(p)::bits == A + B);
    expect("*", to_mpz(p), ma * mb);
    expect("* sign", mpz_class(p.sign()), mpz_class(sgn(ma * mb)));
    expect("* fits", mpz_class(p.fits_bound()), 1);
  }
  const int c = cmp(ma, mb);
  const int want = (c > 0) - (c < 0);
  expect("compare", mpz_class(compare(a, b)), mpz_class(want));
  const int rel = (a < b) | (a <= b) << 1 | (a > b) << 2 | (a >= b) << 3 | (a == b) << 4;
  const int want_rel = (want < 0) | (want <= 0) << 1 | (want > 0) << 2 | (want >= 0) << 3 | (want == 0) << 4;
  expect("relations", mpz_class(rel), mpz_class(want_rel));
}

template <int A, int B>
long check_pair(std::uint64_t seed) {
  Tally t;
  for (const auto& x : boundary_values(A))
    for (const auto& y : boundary_values(B)) check_ops<A, B>(x, y, t);
  // Also each width's boundaries against the other's (2^A vs 2^B edges interleave).
  std::mt19937_64 rng(seed * 1000003 + A * 1000 + B);
  for (int i = 0; i < kRandomPairs; ++i) {
    const mpz_class x = abs(random_value(rng, A)), y = abs(random_value(rng, B));
    check_ops<A, B>(x, y, t);
    check_ops<A, B>(-x, y, t);
    check_ops<A, B>(x, -y, t);
    check_ops<A, B>(-x, -y, t);
  }
  // Equal magnitudes stress compare/subtract where only low limbs differ.
  for (int i = 0; i < kRandomPairs / 4; ++i) {
    const mpz_class x = random_value(rng, std::min(A, B));
    const mpz_class y = x + (rng() % 3) - 1;
    if (abs(y) < pow2(std::min(A, B))) check_ops<A, B>(x, y, t);
  }
  EXPECT_EQ(t.failures, 0) << "Int<" << A << "> with Int<" << B << ">";
  return t.checks;
}

template <int... AB>
void check_pairs(long min_checks) {
  long checks = 0;
  ((checks += check_pair<AB / 1000, AB % 1000>(42)), ...);
  EXPECT_GE(checks, min_checks);  // guards against the generators silently producing nothing
}

TEST(IntOracle, SameWidth) {
  check_pairs<1001, 26026, 27027, 53053, 55055, 62062, 63063, 64064, 79079, 83083, 106106, 107107, 126126, 127127,
              128128, 160160, 162162, 186186, 188188, 190190, 191191, 192192, 241241, 243243, 255255>(25 * 6000);
}

TEST(IntOracle, GeometryProducts) {
  // classify and Cramer products: plane coefficient x point coordinate, minors.
  check_pairs<53188, 188053, 79162, 162079, 53053, 106053, 53106, 106079, 79106, 53055, 55053, 26027, 27026, 26053,
              27055, 53160, 55162, 79083, 83079, 106107, 107106, 53186, 81162, 27188, 26162, 53107, 55107, 107079, 1254,
              254001, 127128, 128127, 63064, 64063, 63063, 64064, 126001, 62065, 191064, 192063>(40 * 6000);
}

TEST(IntOracle, MixedSums) {
  // Sums and comparisons of differently sized terms (sign extension across limbs).
  check_pairs<241026, 26241, 243241, 241243, 162188, 188162, 160186, 107188, 53241, 241053, 27255, 255027, 243255,
              255243, 1255, 126190, 190126, 63191, 191063>(19 * 6000);
}

}  // namespace
}  // namespace ember::test
