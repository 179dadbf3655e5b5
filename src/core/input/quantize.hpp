#pragma once
// One affine map from the caller's double coordinates onto the exact integer
// grid |x| <= 2^25, shared by all operands of an operation, and its inverse.
//
// The scale is a power of two 2^k and the centre a multiple of 2^-k, so
//   quantize(x) = round(x * 2^k) - C      (C = centre * 2^k, an integer)
// is exact up to the one rounding to the grid (integer and dyadic inputs whose
// precision fits the grid survive unchanged), and the inverse of an exact
// rational grid point X/W is (X + C*W) / W * 2^-k: one correctly rounded
// division followed by an exact power-of-two scaling. Choosing 2^k instead of
// the largest possible scale costs at most one bit of the 25.
#include <cstdint>
#include <span>

#include "geometry/plane.hpp"
#include "geometry/point.hpp"
#include "ember/mesh.hpp"

namespace ember {

class Quantizer {
 public:
  /// Largest |coordinate| a quantized point may have. Two grid units stay free
  /// below 2^25 so the root box can be padded and its reference point placed
  /// outside all geometry.
  static constexpr std::int64_t kLimit = kCoordLimit - 2;
  /// |k| bound: 2^k and 2^-k stay normal doubles. fit/fit_box throw for
  /// models whose extent would need a finer grid (below ~1e-294).
  static constexpr int kMaxExponent = 1000;

  Quantizer() = default;
  /// The map for these points (finite values; throws ember::Error otherwise).
  /// Only the listed points are considered: pass the referenced vertices.
  static Quantizer fit(std::span<const Vec3d> points);
  /// The map for a bounding box [lo, hi] (each lo <= hi, all finite).
  static Quantizer fit_box(const Vec3d& lo, const Vec3d& hi);

  IntPoint quantize(const Vec3d& p) const;
  /// Correctly rounded value of an exact homogeneous point in caller units.
  Vec3d dequantize(const Point& p) const;
  Vec3d dequantize(const IntPoint& p) const;

  int exponent() const { return k_; }                     ///< scale = 2^exponent
  const std::int64_t* centre_grid() const { return c_; }  ///< centre * 2^k, per axis
  double grid_spacing() const;                            ///< 2^-k in caller units
  /// Every grid point with |coordinate| <= kCoordLimit dequantizes exactly:
  /// |centre| + kCoordLimit < 2^53 on every axis, so x + centre is a double
  /// and scaling by 2^-k (normal) is exact. Then the rounded corners of a
  /// grid triangle are the triangle itself, scaled by 2^-k and moved.
  bool grid_points_exact() const;

 private:
  int k_ = 0;
  double scale_ = 1, inv_scale_ = 1;  ///< 2^k and 2^-k: multiplying by them is exact (|k| <= 1000)
  std::int64_t c_[3] = {0, 0, 0};
};

}  // namespace ember
