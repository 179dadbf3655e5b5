#pragma once
// The GMP oracle for correctly rounded conversions to double: nearest, ties
// to even, +0 for zero (ratio_to_double, Quantizer::dequantize).
#include <gmpxx.h>
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstring>

namespace ember::test {

/// True iff d is the exact value q rounded to the nearest double, ties to
/// even (+0 for 0). Exact: every comparison in mpq.
inline ::testing::AssertionResult rounds_correctly(const mpq_class& q, double d) {
  auto fail = [&](const char* why) {
    return ::testing::AssertionFailure() << why << ": " << q << " gave " << std::hexfloat << d;
  };
  if (!std::isfinite(d)) return fail("not finite");
  if (q == 0) return d == 0.0 && !std::signbit(d) ? ::testing::AssertionSuccess() : fail("zero must give +0");
  if ((d < 0) != (q < 0) || d == 0) return fail("wrong sign");
  const mpq_class here(d);
  const mpq_class below(std::nextafter(d, 0.0)), above(std::nextafter(d, d * 2));
  const mpq_class err = abs(q - here), err_below = abs(q - below), err_above = abs(q - above);
  if (err > err_below || err > err_above) return fail("not nearest");
  if (err == err_below || err == err_above) {
    std::uint64_t bits;
    std::memcpy(&bits, &d, sizeof bits);
    if (bits & 1) return fail("tie not rounded to even");
  }
  return ::testing::AssertionSuccess();
}

}  // namespace ember::test
