#pragma once
// GMP reference implementations for the geometry tests: every predicate is
// recomputed with unbounded integers/rationals, independently of the minor
// sharing and bit budgets of the library code.
#include <gmpxx.h>

#include <array>
#include <cstdint>
#include <random>

#include "geometry/geometry.hpp"
#include "support/int_gmp.hpp"

namespace ember::test {

inline mpz_class mpz64(std::int64_t v) { return mpz_class(static_cast<long>(v)); }

using MpPlane = std::array<mpz_class, 4>;
using MpPoint = std::array<mpz_class, 4>;  // x, y, z, w

inline MpPlane to_mp(const Plane& p) { return {to_mpz(p.a), to_mpz(p.b), to_mpz(p.c), to_mpz(p.d)}; }
inline MpPoint to_mp(const Point& p) { return {to_mpz(p.x), to_mpz(p.y), to_mpz(p.z), to_mpz(p.w)}; }
inline MpPoint to_mp(const IntPoint& p) { return {mpz64(p.x), mpz64(p.y), mpz64(p.z), 1}; }

/// -1, 0, +1 (gmpxx's sgn may return any signed value).
inline int sign_of(const mpz_class& v) { return v > 0 ? 1 : (v < 0 ? -1 : 0); }

inline mpz_class dot(const MpPlane& s, const MpPoint& x) {
  return s[0] * x[0] + s[1] * x[1] + s[2] * x[2] + s[3] * x[3];
}

/// Plane through three grid points with normal (p1-p0)x(p2-p0).
inline MpPlane oracle_support(const IntPoint& p0, const IntPoint& p1, const IntPoint& p2) {
  const mpz_class ux = mpz64(p1.x) - p0.x, uy = mpz64(p1.y) - p0.y, uz = mpz64(p1.z) - p0.z;
  const mpz_class vx = mpz64(p2.x) - p0.x, vy = mpz64(p2.y) - p0.y, vz = mpz64(p2.z) - p0.z;
  MpPlane r{uy * vz - uz * vy, uz * vx - ux * vz, ux * vy - uy * vx, 0};
  r[3] = -(r[0] * p0.x + r[1] * p0.y + r[2] * p0.z);
  return r;
}

inline mpz_class det3(const mpz_class& a, const mpz_class& b, const mpz_class& c, const mpz_class& d,
                      const mpz_class& e, const mpz_class& f, const mpz_class& g, const mpz_class& h,
                      const mpz_class& i) {
  return a * (e * i - f * h) - b * (d * i - f * g) + c * (d * h - e * g);
}

/// Cramer: solves n.X + d*w = 0 for the three planes; w = -det(N), then w > 0.
/// Returns w = 0 (and x, y, z as computed) if the normals are dependent.
inline MpPoint oracle_intersect(const MpPlane& p, const MpPlane& q, const MpPlane& r) {
  const mpz_class det = det3(p[0], p[1], p[2], q[0], q[1], q[2], r[0], r[1], r[2]);
  // Cartesian solution x_i = det(N with column i replaced by -d) / det.
  const mpz_class dx = det3(-p[3], p[1], p[2], -q[3], q[1], q[2], -r[3], r[1], r[2]);
  const mpz_class dy = det3(p[0], -p[3], p[2], q[0], -q[3], q[2], r[0], -r[3], r[2]);
  const mpz_class dz = det3(p[0], p[1], -p[3], q[0], q[1], -q[3], r[0], r[1], -r[3]);
  if (det < 0) return {-dx, -dy, -dz, -det};
  return {dx, dy, dz, det};
}

/// Number of bits of |v| (|v| < 2^result).
inline int bits_of(const mpz_class& v) { return v == 0 ? 0 : static_cast<int>(mpz_sizeinbase(v.get_mpz_t(), 2)); }

/// Random grid points: a third at the corners of the cube, a third close to
/// them, a third uniform over the full range [-2^25, 2^25].
class Gen {
 public:
  explicit Gen(std::uint64_t seed) : rng_(seed) {}
  std::int64_t coord() {
    const std::int64_t L = kCoordLimit;
    switch (rng_() % 3) {
      case 0: return (rng_() & 1) ? L : -L;
      case 1:
        return (rng_() & 1) ? L - static_cast<std::int64_t>(rng_() % 64) : -L + static_cast<std::int64_t>(rng_() % 64);
      default: return std::uniform_int_distribution<std::int64_t>(-L, L)(rng_);
    }
  }
  std::int64_t uniform(std::int64_t lo, std::int64_t hi) {
    return std::uniform_int_distribution<std::int64_t>(lo, hi)(rng_);
  }
  IntPoint point() { return {coord(), coord(), coord()}; }
  IntPoint small_point(std::int64_t r) { return {uniform(-r, r), uniform(-r, r), uniform(-r, r)}; }
  std::array<IntPoint, 3> triangle() {
    for (;;) {
      std::array<IntPoint, 3> t{point(), point(), point()};
      if (supporting_plane(t[0], t[1], t[2])) return t;
    }
  }
  Plane plane(char kind) {
    if (kind == 'S') {
      const auto t = triangle();
      return *supporting_plane(t[0], t[1], t[2]);
    }
    if (kind == 'E') {
      const auto t = triangle();
      const int e = static_cast<int>(rng_() % 3);
      return edge_plane(t[e], t[(e + 1) % 3], *supporting_plane(t[0], t[1], t[2]));
    }
    const Plane a = axis_plane(static_cast<int>(rng_() % 3), coord());
    return (rng_() & 1) ? a : -a;
  }
  std::mt19937_64& rng() { return rng_; }

 private:
  std::mt19937_64 rng_;
};

}  // namespace ember::test
