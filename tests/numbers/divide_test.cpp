// floor_scaled_ratio against GMP: random widths used by the geometry, all
// sign combinations, exact multiples (remainder zero) and off-by-one values.
#include <gmpxx.h>
#include <gtest/gtest.h>

#include <random>

#include "numbers/divide.hpp"

namespace ember::test {
namespace {

mpz_class to_mpz(const std::string& s) { return mpz_class(s); }

template <int A, int B>
void check(const Int<A>& n, const Int<B>& d, int shift) {
  const mpz_class N = to_mpz(n.to_string()), D = to_mpz(d.to_string());
  mpz_class q;
  mpz_fdiv_q(q.get_mpz_t(), mpz_class(N << shift).get_mpz_t(), D.get_mpz_t());
  const __int128 got = floor_scaled_ratio(n, d, shift);
  const bool neg = got < 0;
  const unsigned __int128 mag = neg ? -static_cast<unsigned __int128>(got) : static_cast<unsigned __int128>(got);
  mpz_class g = mpz_class(static_cast<unsigned long>(mag >> 64));
  g = (g << 64) + mpz_class(static_cast<unsigned long>(mag));
  if (neg) g = -g;
  EXPECT_EQ(g, q) << N << " * 2^" << shift << " / " << D;
}

TEST(Divide, HomogeneousCoordinatesToDyadicGrid) {
  // x / w with |x / w| <= 2^26, as for points inside the grid: build x = w * c + e.
  std::mt19937_64 rng(5);
  for (int i = 0; i < 20000; ++i) {
    const int wbits = 1 + static_cast<int>(rng() % 100);
    Int<162> w = Int<162>::assume_bound(Int<127>(static_cast<i128>(rng() >> (64 - std::min(wbits, 63)))) + Int<127>(1));
    if (i % 2) w = Int<162>::assume_bound(w * Int<60>(static_cast<std::int64_t>(rng() >> 5)) + Int<1>(0));
    if (rng() % 2) w = -w;
    const std::int64_t c = static_cast<std::int64_t>(rng() % (std::uint64_t{1} << 26)) - (std::int64_t{1} << 25);
    const std::int64_t e = static_cast<std::int64_t>(rng() % 1000) - 500;
    const Int<188> x = Int<188>::assume_bound(w * Int<27>(c) + Int<20>(i % 3 == 0 ? 0 : e));
    check(x, w, static_cast<int>(rng() % 55));
  }
}

TEST(Divide, SmallExactCasesAndSigns) {
  for (std::int64_t n = -40; n <= 40; ++n)
    for (std::int64_t d = -9; d <= 9; ++d) {
      if (d == 0) continue;
      for (int s : {0, 1, 5, 36, 54, 64}) check(Int<8>(n), Int<5>(d), s);
    }
}

}  // namespace
}  // namespace ember::test
