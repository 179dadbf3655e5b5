#include "ember/core/quantize.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <string>

#include "ember/error.hpp"
#include "ember/numbers/ratio.hpp"

namespace ember {

namespace {
double coord(const Vec3d& p, int i) { return i == 0 ? p.x : (i == 1 ? p.y : p.z); }
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
    std::snprintf(msg, sizeof msg, "the model's extent is %.3g, below the smallest the grid supports (%.2g",
                  2 * half, std::ldexp(2.0 * static_cast<double>(kLimit - 2), -kMaxExponent));
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
    if (!(std::fabs(c) < 9.0e18)) throw Error("coordinates too large to quantize: the model is too far from the origin for its size");
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
