// ns/op of the exact-integer kernel: the products and the 4-term dot product
// behind classify, and the correctly rounded export division.
//
// Inputs are pools of random full-range values (random signs, deterministic
// seed) walked with a stride so the compiler cannot fold or hoist the work
// and sign branches are as unpredictable as on real data.
#include <benchmark/benchmark.h>

#include <cstdint>
#include <random>
#include <vector>

#include "numbers/int.hpp"
#include "numbers/ratio.hpp"

namespace {

using ember::Int;

constexpr std::size_t kPool = 1024;  // power of two: index masking is cheap

/// Uniform value with |v| < 2^Bits (two's complement limbs, random sign).
template <int Bits>
Int<Bits> random_int(std::mt19937_64& rng) {
  constexpr int L = Int<Bits>::limbs;
  std::array<std::uint64_t, L> mag{};
  for (int i = 0; i < L; ++i) {
    const int lo = 64 * i;
    const int keep = Bits - lo >= 64 ? 64 : (Bits - lo > 0 ? Bits - lo : 0);
    mag[i] = keep == 64 ? rng() : (keep == 0 ? 0 : rng() & ((std::uint64_t{1} << keep) - 1));
  }
  const Int<Bits> v = Int<Bits>::from_limbs(mag);
  return (rng() & 1) ? -v : v;
}

template <int Bits>
std::vector<Int<Bits>> pool(std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::vector<Int<Bits>> v(kPool);
  for (auto& x : v) x = random_int<Bits>(rng);
  return v;
}

template <int A, int B>
void BM_Mul(benchmark::State& state) {
  const auto a = pool<A>(1);
  const auto b = pool<B>(2);
  std::size_t i = 0;
  for (auto _ : state) {
    auto p = a[i & (kPool - 1)] * b[(i * 7 + 3) & (kPool - 1)];
    benchmark::DoNotOptimize(p);
    ++i;
  }
}
BENCHMARK(BM_Mul<53, 188>)->Name("Int53xInt188");
BENCHMARK(BM_Mul<79, 162>)->Name("Int79xInt162");
BENCHMARK(BM_Mul<53, 53>)->Name("Int53xInt53");
BENCHMARK(BM_Mul<106, 79>)->Name("Int106xInt79");

/// classify-style dot product: sign(p0·x0 + p1·x1 + p2·x2 + d·w).
void BM_Dot4Sign(benchmark::State& state) {
  const auto p = pool<53>(3);
  const auto x = pool<188>(4);
  const auto d = pool<162>(5);
  const auto w = pool<79>(6);
  std::size_t i = 0;
  for (auto _ : state) {
    const std::size_t k = i & (kPool - 1);
    const std::size_t j = (i * 5 + 1) & (kPool - 1);
    const auto s = (p[k] * x[j] + p[(k + 1) & (kPool - 1)] * x[(j + 1) & (kPool - 1)]) +
                   (p[(k + 2) & (kPool - 1)] * x[(j + 2) & (kPool - 1)] + d[k] * w[j]);
    benchmark::DoNotOptimize(s.sign());
    ++i;
  }
}
BENCHMARK(BM_Dot4Sign)->Name("Dot4Sign_3x53x188_162x79");

/// Export of a homogeneous coordinate x_i / x4 (SSS point widths).
template <int A, int B>
void BM_Ratio(benchmark::State& state) {
  const auto n = pool<A>(7);
  const auto d = pool<B>(8);
  std::size_t i = 0;
  for (auto _ : state) {
    const std::size_t k = i & (kPool - 1);
    const auto& den = d[(i * 3 + 1) & (kPool - 1)];
    double r = den.is_zero() ? 0.0 : ember::ratio_to_double(n[k], den);
    benchmark::DoNotOptimize(r);
    ++i;
  }
}
BENCHMARK(BM_Ratio<188, 162>)->Name("RatioToDouble_188_162");
BENCHMARK(BM_Ratio<84, 55>)->Name("RatioToDouble_84_55");
BENCHMARK(BM_Ratio<27, 1>)->Name("RatioToDouble_27_1");

}  // namespace
