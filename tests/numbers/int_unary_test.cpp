// Oracle tests of Int unary operations, conversions and multi-term expressions,
// plus compile-time (constexpr) evaluation.
#include <gtest/gtest.h>

#include <cmath>

#include "support/numbers_oracle.hpp"

namespace ember::test {
namespace {

constexpr int kRandom = 4000;

template <int A>
std::vector<mpz_class> sample(std::mt19937_64& rng) {
  std::vector<mpz_class> v = boundary_values(A);
  for (int i = 0; i < kRandom; ++i) v.push_back(random_value(rng, A));
  return v;
}

/// Negation, abs, sign, predicates, to_string, to_double, round trip through limbs.
template <int A>
void check_unary(std::mt19937_64& rng, long& checks) {
  for (const auto& m : sample<A>(rng)) {
    const Int<A> a = from_mpz<A>(m);
    ++checks;
    ASSERT_EQ(to_mpz(a), m) << "round trip Int<" << A << ">";
    ASSERT_EQ(to_mpz(-a), -m) << "negation Int<" << A << "> of " << m;
    ASSERT_EQ(to_mpz(a.abs()), abs(m)) << "abs Int<" << A << "> of " << m;
    ASSERT_EQ(a.sign(), sgn(m)) << "sign Int<" << A << "> of " << m;
    ASSERT_EQ(a.negative(), m < 0);
    ASSERT_EQ(a.is_zero(), m == 0);
    ASSERT_TRUE(a.fits_bound());
    ASSERT_EQ(a.to_string(), m.get_str()) << "to_string Int<" << A << ">";
    // to_double: a few roundings of limbs; relative error well below 2^-50.
    const double d = a.to_double();
    const double want = m.get_d();  // truncates, also within 2^-52 relative
    ASSERT_LE(std::fabs(d - want), std::ldexp(std::fabs(want), -50)) << "to_double Int<" << A << "> of " << m;
  }
}

/// Widening to W > A keeps the value; assume_bound narrows values that fit.
template <int A, int W>
void check_widen_narrow(std::mt19937_64& rng, long& checks) {
  static_assert(W > A);
  for (const auto& m : sample<A>(rng)) {
    const Int<W> w = from_mpz<A>(m);  // implicit widening
    ASSERT_EQ(to_mpz(w), m) << "widen Int<" << A << "> -> Int<" << W << "> of " << m;
    for (int i = Int<A>::limbs; i < Int<W>::limbs + 1; ++i)
      ASSERT_EQ(w.limb(i), m < 0 ? ~std::uint64_t{0} : 0) << "sign extension, limb " << i;
    const Int<A> back = Int<A>::assume_bound(w);
    ASSERT_EQ(to_mpz(back), m) << "assume_bound Int<" << W << "> -> Int<" << A << "> of " << m;
    ASSERT_TRUE(back == w);
    ++checks;
  }
}

TEST(IntOracle, ApproxToDoubleOfI128IsWithinThreeRoundings) {
  // Random values of every bit length, both signs, and the edges of the two
  // branches (2^63), of exact high limbs (2^117) and of the range (2^127 - 1).
  std::mt19937_64 rng(23);
  std::vector<mpz_class> values = boundary_values(127);
  for (int bits = 1; bits <= 127; ++bits)
    for (int i = 0; i < 200; ++i) values.push_back(random_value(rng, bits));
  const std::vector<mpz_class> edges{pow2(63), pow2(64) - 1, pow2(64), pow2(53) + 1, pow2(117) + 1, pow2(127) - 1};
  for (const mpz_class& edge : edges) {
    values.push_back(edge);
    values.push_back(edge - 1);
    values.push_back(-edge);
  }
  long checked = 0;
  for (const mpz_class& m : values) {
    const i128 v = from_mpz<127>(m).raw();  // |m| < 2^127: inside the documented range
    const double d = approx_to_double(v);
    const mpq_class err = abs(mpq_class(d) - mpq_class(m));
    // 3 roundings: (1 + 2^-53)^3 - 1 < 2^-51.
    ASSERT_LE(err, abs(mpq_class(m)) / mpq_class(pow2(51))) << m;
    ASSERT_EQ(d < 0, m < 0) << m;
    ++checked;
  }
  EXPECT_GT(checked, 25000);
}

TEST(IntOracle, Unary) {
  std::mt19937_64 rng(7);
  long n = 0;
  check_unary<1>(rng, n);
  check_unary<26>(rng, n);
  check_unary<27>(rng, n);
  check_unary<53>(rng, n);
  check_unary<55>(rng, n);
  check_unary<62>(rng, n);
  check_unary<63>(rng, n);
  check_unary<64>(rng, n);
  check_unary<79>(rng, n);
  check_unary<83>(rng, n);
  check_unary<106>(rng, n);
  check_unary<107>(rng, n);
  check_unary<126>(rng, n);
  check_unary<127>(rng, n);
  check_unary<128>(rng, n);
  check_unary<160>(rng, n);
  check_unary<162>(rng, n);
  check_unary<186>(rng, n);
  check_unary<188>(rng, n);
  check_unary<191>(rng, n);
  check_unary<192>(rng, n);
  check_unary<241>(rng, n);
  check_unary<243>(rng, n);
  check_unary<255>(rng, n);
  EXPECT_GE(n, 24L * kRandom);
}

TEST(IntOracle, WidenAndAssumeBound) {
  std::mt19937_64 rng(11);
  long n = 0;
  check_widen_narrow<26, 27>(rng, n);
  check_widen_narrow<27, 53>(rng, n);
  check_widen_narrow<53, 63>(rng, n);
  check_widen_narrow<53, 64>(rng, n);
  check_widen_narrow<63, 64>(rng, n);
  check_widen_narrow<53, 188>(rng, n);
  check_widen_narrow<79, 83>(rng, n);
  check_widen_narrow<106, 127>(rng, n);
  check_widen_narrow<127, 128>(rng, n);
  check_widen_narrow<107, 162>(rng, n);
  check_widen_narrow<160, 162>(rng, n);
  check_widen_narrow<188, 191>(rng, n);
  check_widen_narrow<191, 192>(rng, n);
  check_widen_narrow<162, 241>(rng, n);
  check_widen_narrow<243, 255>(rng, n);
  check_widen_narrow<1, 255>(rng, n);
  check_widen_narrow<26, 243>(rng, n);
  EXPECT_GE(n, 17L * kRandom);
}

TEST(IntOracle, MultiTermExpressions) {
  std::mt19937_64 rng(13);
  for (int i = 0; i < 20000; ++i) {
    // classify-style dot product: three Int<53>*Int<188> and one Int<162>*Int<79>.
    mpz_class p[3], x[3];
    for (int k = 0; k < 3; ++k) p[k] = random_value(rng, 53), x[k] = random_value(rng, 188);
    const mpz_class d = random_value(rng, 162), w = random_value(rng, 79);
    const auto dot = (from_mpz<53>(p[0]) * from_mpz<188>(x[0]) + from_mpz<53>(p[1]) * from_mpz<188>(x[1])) +
                     (from_mpz<53>(p[2]) * from_mpz<188>(x[2]) + from_mpz<162>(d) * from_mpz<79>(w));
    static_assert(decltype(dot)::bits == 243, "241-bit products, two levels of sums: 241 + 2");
    const mpz_class want = p[0] * x[0] + p[1] * x[1] + p[2] * x[2] + d * w;
    ASSERT_EQ(to_mpz(dot), want);
    ASSERT_EQ(dot.sign(), sgn(want));

    // Triple product Int<53>^3 and the chained Int<106>*Int<79>.
    const mpz_class a = random_value(rng, 53), b = random_value(rng, 53), c = random_value(rng, 53);
    const auto abc = from_mpz<53>(a) * from_mpz<53>(b) * from_mpz<53>(c);
    static_assert(decltype(abc)::bits == 159, "53 * 3");
    ASSERT_EQ(to_mpz(abc), a * b * c);
    const mpz_class e = random_value(rng, 106), f = random_value(rng, 79);
    ASSERT_EQ(to_mpz(from_mpz<106>(e) * from_mpz<79>(f)), e * f);

    // Sum of four Int<241> at full range, then compared with an Int<243>.
    mpz_class s[4];
    for (auto& v : s) v = random_value(rng, 241);
    const auto sum = (from_mpz<241>(s[0]) + from_mpz<241>(s[1])) + (from_mpz<241>(s[2]) - from_mpz<241>(s[3]));
    const mpz_class want_sum = s[0] + s[1] + s[2] - s[3];
    ASSERT_EQ(to_mpz(sum), want_sum);
    const mpz_class other = random_value(rng, 243);
    ASSERT_EQ(compare(sum, from_mpz<243>(other)), sgn(want_sum - other));
  }
  // Extremes of the dot product: all terms at their bound with the same sign.
  const mpz_class p = pow2(53) - 1, x = pow2(188) - 1, d = pow2(162) - 1, w = pow2(79) - 1;
  const auto dot =
      from_mpz<53>(p) * from_mpz<188>(x) + from_mpz<53>(-p) * from_mpz<188>(-x) + from_mpz<162>(d) * from_mpz<79>(w);
  EXPECT_EQ(to_mpz(dot), 2 * p * x + d * w);
}

// ---- compile-time evaluation ----
constexpr Int<188> kBig = Int<188>::from_limbs({~std::uint64_t{0}, 0x123456789abcdefULL, 0x0fffffffffffffffULL});
constexpr Int<53> kSmall = Int<53>((std::int64_t{1} << 53) - 1);
constexpr auto kProduct = kSmall * kBig;
constexpr auto kNegProduct = (-kSmall) * kBig;
static_assert(decltype(kProduct)::bits == 241);
// limb 0: (2^53-1)·(2^64-1) ≡ -(2^53-1) = 2^64 - 2^53 + 1 (mod 2^64).
static_assert(kProduct.limb(0) == (~std::uint64_t{0} << 53) + 1);
static_assert(kProduct.sign() == 1 && kNegProduct.sign() == -1);
static_assert(-kNegProduct == kProduct && kNegProduct + kProduct == Int<1>(0));
static_assert((Int<27>(-(1 << 26)) * Int<26>((1 << 25) + 3)).raw() == -(std::int64_t{1} << 26) * ((1 << 25) + 3));
static_assert((Int<79>(i128{1} << 78) * Int<79>(-(i128{1} << 78))).limb(2) == std::uint64_t{0} - (1ULL << 28));
static_assert(compare(Int<255>(-1), Int<255>(1)) < 0 && Int<255>(5) > Int<26>(4));
static_assert(Int<53>(-7).abs() == Int<3>(7) && Int<243>(0).sign() == 0);

}  // namespace
}  // namespace ember::test
