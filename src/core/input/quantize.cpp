#include "core/input/quantize.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdio>
#include <limits>
#include <optional>
#include <string>

#include "ember/error.hpp"
#include "numbers/ratio.hpp"

namespace ember {

namespace {

using i128 = __int128;

double coord(const Vec3d& p, int i) { return i == 0 ? p.x : (i == 1 ? p.y : p.z); }

/// v, if |v| < 2^120 (then it is an i128 and products with 50-bit factors
/// still fit).
template <int B>
std::optional<i128> narrow(const Int<B>& v) {
  static_assert(Int<B>::limbs == 3, "Point's coordinates and w have three limbs");
  const auto hi = static_cast<std::int64_t>(v.limb(1));
  constexpr std::int64_t kHigh = std::int64_t{1} << 56;
  if (v.limb(2) != (hi < 0 ? ~std::uint64_t{0} : 0) || hi >= kHigh || hi < -kHigh) return std::nullopt;
  return static_cast<i128>(static_cast<unsigned __int128>(v.limb(1)) << 64 | v.limb(0));
}

/// x / w + c rounded to the nearest double, for 0 < w and |x|, w < 2^120 and
/// |c| < 2^63, where double arithmetic can tell (else nullopt, for
/// ratio_to_double: values within 2^-50 of a rounding boundary, about one in
/// 2^22 at 2^25 grid units, and values below 16 grid units, where half a gap
/// is at most that, or beyond 2^52).
/// The crossing points of the direct route are such ratios (|x| < 2^110,
/// w < 2^84): this is 3-4x cheaper than the three-limb ratio.
///  1. q = floor(x / w) and r = x - q w in [0, w) exactly: from a double
///     quotient (error < 2 where |x / w| < 2^50), truncated (std::floor is
///     a libm call on the baseline target), corrected in i128.
///  2. The value is N + f with N = q + c (int64) and f = r / w in [0, 1);
///     for |N| in [1, 2^52) or N <= -2 (|value| >= 1/2), N is exact in
///     double, and fd = r / w in double errs by less than D = 2^-50 (three
///     roundings in each conversion, one in the division, times f < 1).
///  3. s = N + fd rounded, and its error e exactly (Fast2Sum: |N| >= fd).
///     The value lies within D of s + e; s is its correct rounding when
///     that interval lies strictly inside s's rounding interval (half the
///     gap to each neighbouring double; the gap below a power of two is half
///     the one above), so there are never ties to break.
/// `dw` is approx_to_double(w), shared by a point's three coordinates.
std::optional<double> offset_ratio_to_double(i128 x, i128 w, double dw, std::int64_t c) {
  const double qd = approx_to_double(x) / dw;
  if (!(std::fabs(qd) < 0x1p50)) return std::nullopt;
  auto q = static_cast<std::int64_t>(qd);  // truncated: within 3 of floor(x / w)
  i128 r = x - static_cast<i128>(q) * w;   // |q w| < |x| + 3 w < 2^122
  for (int i = 0; i < 3 && r < 0; ++i) r += w, --q;
  for (int i = 0; i < 3 && r >= w; ++i) r -= w, ++q;
  if (r < 0 || r >= w) return std::nullopt;  // never, by the bound in 1.
  const std::int64_t n = q + c;              // |q| < 2^51, |c| < 9.0e18 < 2^63 - 2^51
  constexpr std::int64_t kExact = std::int64_t{1} << 52;
  if (n >= kExact || n < -kExact || n == 0 || n == -1) return std::nullopt;
  const double nd = static_cast<double>(n), fd = approx_to_double(r) / dw;
  const double sum = nd + fd, err = fd - (sum - nd);
  constexpr double kFractionError = 0x1p-50;
  const std::uint64_t bits = std::bit_cast<std::uint64_t>(std::fabs(sum));
  const std::uint64_t exponent = bits >> 52;  // |sum| >= 1/2: a normal double
  const double half_gap_away = std::bit_cast<double>((exponent - 53) << 52);
  const double half_gap_toward =
      (bits & ((std::uint64_t{1} << 52) - 1)) == 0 ? std::bit_cast<double>((exponent - 54) << 52) : half_gap_away;
  const double away = sum > 0 ? err : -err;  // the offset from sum, away from 0
  // Both bounds are exact: powers of two 2^-55 .. 2^0 minus 2^-50.
  if (away < half_gap_away - kFractionError && away > kFractionError - half_gap_toward) return sum;
  return std::nullopt;
}

}  // namespace

Quantizer Quantizer::fit(std::span<const Vec3d> points) {
  if (points.empty()) return Quantizer{};
  Vec3d lo = points[0], hi = points[0];
  for (const Vec3d& p : points) {
    if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
      throw Error("non-finite vertex coordinate (NaN or infinity); every coordinate must be a finite number");
    lo = {std::min(lo.x, p.x), std::min(lo.y, p.y), std::min(lo.z, p.z)};
    hi = {std::max(hi.x, p.x), std::max(hi.y, p.y), std::max(hi.z, p.z)};
  }
  return fit_box(lo, hi);
}

Quantizer Quantizer::fit_box(const Vec3d& lo, const Vec3d& hi) {
  Quantizer q;
  double half = 0;
  for (int i = 0; i < 3; ++i) {
    const double a = coord(lo, i), b = coord(hi, i);
    if (!std::isfinite(a) || !std::isfinite(b) || a > b) throw Error("invalid bounding box for quantization");
    // (b - a) may overflow for extreme inputs; halve first.
    half = std::max(half, b / 2 - a / 2);
  }
  // Largest k with (half + grid spacing) * 2^k <= kLimit - 1: the centre is
  // rounded to the grid (<= 1/2 unit off) and each point rounds by <= 1/2 unit.
  int k = 0;
  if (half > 0) {
    // From the exponent, not log2(limit / half): that ratio overflows for
    // subnormal extents.
    k = 24 - std::ilogb(half);
    while (std::ldexp(half, k) > static_cast<double>(kLimit - 2)) --k;
    while (std::ldexp(half, k + 1) <= static_cast<double>(kLimit - 2)) ++k;
  } else {
    k = 0;  // a single point: any scale works, keep the identity
  }
  // 2^k must be a normal double (exact scaling both ways). A model smaller
  // than that allows (extent below ~1e-294, subnormal range) would be
  // quantized onto too coarse a grid and silently collapse: refuse it.
  if (k > kMaxExponent) {
    char msg[96];
    std::snprintf(msg, sizeof msg, "the model's extent is %.3g, below the smallest the grid supports (%.2g", 2 * half,
                  std::ldexp(2.0 * static_cast<double>(kLimit - 2), -kMaxExponent));
    throw Error(std::string("coordinates too small to quantize: ") + msg +
                ", near the subnormal range); scale the model up (by a power of two to keep coordinates exact)");
  }
  k = std::max(k, -kMaxExponent);
  q.k_ = k;
  q.scale_ = std::ldexp(1.0, k);
  q.inv_scale_ = std::ldexp(1.0, -k);
  for (int i = 0; i < 3; ++i) {
    const double mid = coord(lo, i) / 2 + coord(hi, i) / 2;
    const double c = std::nearbyint(std::ldexp(mid, k));
    if (!(std::fabs(c) < 9.0e18))
      throw Error("coordinates too large to quantize: the model is too far from the origin for its size");
    q.c_[i] = static_cast<std::int64_t>(c);
  }
  return q;
}

IntPoint Quantizer::quantize(const Vec3d& p) const {
  std::int64_t out[3];
  for (int i = 0; i < 3; ++i) {
    const double v = coord(p, i);
    if (!std::isfinite(v)) throw Error("non-finite vertex coordinate (NaN or infinity)");
    const double g = std::nearbyint(v * scale_);
    // |g - c| <= kLimit for points inside the fitted box; anything else is a caller error.
    const double rel = g - static_cast<double>(c_[i]);
    if (!(std::fabs(rel) <= static_cast<double>(kLimit)))
      throw Error("point outside the quantization box (was the map fitted to all operands?)");
    out[i] = static_cast<std::int64_t>(g) - c_[i];
  }
  return IntPoint{out[0], out[1], out[2]};
}

Vec3d Quantizer::dequantize(const Point& p) const {
  // Grid points (w = 1, |x| <= 2^25) are most output vertices.
  if (p.w == PointW(1))
    return dequantize(IntPoint{static_cast<std::int64_t>(p.x.limb(0)), static_cast<std::int64_t>(p.y.limb(0)),
                               static_cast<std::int64_t>(p.z.limb(0))});
  const std::optional<i128> w = narrow(p.w), px = narrow(p.x), py = narrow(p.y), pz = narrow(p.z);
  if (w && px && py && pz) {
    const double dw = approx_to_double(*w);
    const std::optional<double> x = offset_ratio_to_double(*px, *w, dw, c_[0]),
                                y = offset_ratio_to_double(*py, *w, dw, c_[1]),
                                z = offset_ratio_to_double(*pz, *w, dw, c_[2]);
    if (x && y && z) return Vec3d{*x * inv_scale_, *y * inv_scale_, *z * inv_scale_};
  }
  // x = (X + C W) / W * 2^-k: |C| < 9.0e18 < 2^63 (fit_box), W < 2^162 so
  // C W < 2^225, sum < 2^226. Int<63>: one limb, the products' fast path.
  const Int<63> cx(c_[0]), cy(c_[1]), cz(c_[2]);
  const auto x = ratio_to_double(p.x + cx * p.w, p.w);
  const auto y = ratio_to_double(p.y + cy * p.w, p.w);
  const auto z = ratio_to_double(p.z + cz * p.w, p.w);
  return Vec3d{x * inv_scale_, y * inv_scale_, z * inv_scale_};
}

Vec3d Quantizer::dequantize(const IntPoint& p) const {
  // |x| <= 2^25: x + C fits an int64 whose conversion to double is correctly
  // rounded; 2^-k is exact.
  const auto grid = [&](std::int64_t v, int i) { return static_cast<double>(v + c_[i]) * inv_scale_; };
  return Vec3d{grid(p.x, 0), grid(p.y, 1), grid(p.z, 2)};
}

double Quantizer::grid_spacing() const { return std::ldexp(1.0, -k_); }

bool Quantizer::grid_points_exact() const {
  static_assert(kCoordLimit < (std::int64_t{1} << 53), "a grid coordinate is itself a double");
  constexpr std::int64_t kExact = (std::int64_t{1} << 53) - kCoordLimit;
  return std::all_of(c_, c_ + 3, [](std::int64_t c) { return c > -kExact && c < kExact; });
}

}  // namespace ember
