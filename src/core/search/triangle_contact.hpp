#pragma once
// Exact contact tests of two grid triangles (triangle_contact.cpp has the bit budget).
#include <array>
#include <cmath>
#include <cstdint>

#include "core/search/contact_triangle.hpp"
#include "geometry/bounds.hpp"
#include "geometry/plane.hpp"

namespace ember::core {

/// Step 1 alone, for one pair: true if the two non-degenerate triangles meet
/// anywhere except in shared vertices or a shared edge.
bool triangles_meet_improperly(const ContactTriangle& a, const ContactTriangle& b);
/// The same for bare triangles (vertices are shared when their positions are
/// equal); for tests.
bool triangles_meet_improperly(const std::array<IntPoint, 3>& a, const std::array<IntPoint, 3>& b);
/// The closed triangles have a common point, any (shared vertices and
/// touching included): the contact test of triangles of different operands.
bool triangles_meet(const std::array<IntPoint, 3>& a, const std::array<IntPoint, 3>& b);
/// The same, given both grid normals (na = grid_normal of a, nb of b): the
/// test of two triangles that share no vertex id, without the set-up of
/// triangles_meet_improperly (which ends in it when nothing is shared).
bool apart_triangles_meet(const std::array<IntPoint, 3>& a, const std::array<std::int64_t, 3>& na,
                          const std::array<IntPoint, 3>& b, const std::array<std::int64_t, 3>& nb);
/// Every corner of `b` lies strictly on one side of the plane of `a` (normal
/// `na` = grid_normal of a), so the two cannot meet: the cheap rejection that
/// apart_triangles_meet tries first. Exact.
bool beside_plane(const std::array<IntPoint, 3>& a, const std::array<std::int64_t, 3>& na,
                  const std::array<IntPoint, 3>& b);

/// The signs (-1, 0, 1) of a triangle's three corners against a plane.
struct CornerSigns {
  int s[3];
  bool strictly_one_side() const { return (s[0] > 0 && s[1] > 0 && s[2] > 0) || (s[0] < 0 && s[1] < 0 && s[2] < 0); }
};

/// The exact signs of corners against one plane (a triangle's: a corner
/// `origin` and its grid normal `n`), in double where that decides them, for
/// a search that tests many triangles against one plane (the solid path's
/// partner search tests each triangle of a leaf against ~7 others, and most
/// lie beside its plane): ~35 inline instructions per triangle where the
/// exact test's first step was a call of ~110 (128-bit products, spills).
///
/// Bit budget: corners and the origin are grid points (|x| <= 2^25, exact in
/// double), so each difference d_k (|d_k| <= 2^26) is exact, and so are the
/// normal's components (|n_k| < 2^53). The side n . d is then three rounded
/// products and two rounded sums (or fewer roundings where the compiler
/// fuses them): its error is below gamma_3 sum |n_k d_k| <= 3.0001 * 2^-53 *
/// 2^26 * N with N = sum |n_k|, under the margin 2^-25 N (N's own rounding
/// costs a factor 1 - 2^-52). Only corners within ~2^-24 grid units of the
/// plane take the exact side (grid_side).
class PlaneSideFilter {
 public:
  PlaneSideFilter(const IntPoint& origin, const std::array<std::int64_t, 3>& n)
      : origin_(origin),
        normal_(n),
        o_{static_cast<double>(origin.x), static_cast<double>(origin.y), static_cast<double>(origin.z)},
        n_{static_cast<double>(n[0]), static_cast<double>(n[1]), static_cast<double>(n[2])},
        margin_(0x1p-25 * (std::abs(n_[0]) + std::abs(n_[1]) + std::abs(n_[2]))) {
    static_assert(kCoordLimit <= (std::int64_t{1} << 25), "corner - origin exact in double, the margin's 2^26");
  }
  [[gnu::always_inline]] CornerSigns signs(const std::array<IntPoint, 3>& b) const {
    return {{corner_sign(b[0]), corner_sign(b[1]), corner_sign(b[2])}};
  }

 private:
  [[gnu::always_inline]] int corner_sign(const IntPoint& p) const {
    const double s = n_[0] * (static_cast<double>(p.x) - o_[0]) + n_[1] * (static_cast<double>(p.y) - o_[1]) +
                     n_[2] * (static_cast<double>(p.z) - o_[2]);
    if (s > margin_) return 1;
    if (s < -margin_) return -1;
    return exact_sign(p);
  }
  /// Out of line: rarely taken, and its 128-bit products would crowd the
  /// callers' registers.
  [[gnu::noinline]] int exact_sign(const IntPoint& p) const;

  IntPoint origin_;
  std::array<std::int64_t, 3> normal_;
  double o_[3], n_[3], margin_;
};

/// apart_triangles_meet, given the signs of b's corners against a's plane
/// (PlaneSideFilter), which must not be all equal and non-zero (that pair is
/// beside a's plane and does not meet).
bool apart_triangles_meet(const std::array<IntPoint, 3>& a, const std::array<std::int64_t, 3>& na,
                          const std::array<IntPoint, 3>& b, const std::array<std::int64_t, 3>& nb,
                          const CornerSigns& sb);

}  // namespace ember::core
