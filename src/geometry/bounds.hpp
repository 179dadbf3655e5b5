#pragma once
// Bit budgets of the plane-based geometry (B = 25: integer input coordinates
// satisfy |x| <= 2^25). Every type below is the *magnitude* bound of a value,
// i.e. Int<k> holds |v| < 2^k. The predicates in this layer are written so
// that the Int type system derives exactly these widths; the static_asserts
// pin them, so a change in the arithmetic that widens a value fails to compile.
// See docs/geometry.md and /work/shared/reference/numerics.md.
#include <cstdint>
#include <type_traits>

#include "numbers/int.hpp"

namespace ember {

/// Largest allowed magnitude of an input (grid) coordinate.
inline constexpr std::int64_t kCoordLimit = std::int64_t{1} << 25;

/// Grid coordinate: |x| <= 2^25 < 2^26.
using Coord = Int<26>;

/// Difference of two coordinates: |p - q| <= 2^26 < 2^27.
using CoordDiff = Int<27>;

/// Normal component of any plane kind.
/// S (supporting) planes: n = (p1-p0)x(p2-p0); |n_k| is twice the area of the
/// triangle projected onto a coordinate plane; the projection lies in a square
/// of side 2^26, so its area is <= 2^52 / 2 and |n_k| <= 2^52 < 2^53. (The naive
/// type derivation gives 27+27+1 = 55 bits; supporting_plane narrows with
/// assume_bound citing this argument.) E (edge) planes: |m_k| <= 2^26.
/// A (axis) planes: 1.
using NormalCoef = Int<53>;

/// Plane offset. S: |d| = |n.p0| <= (|n_x|+|n_y|+|n_z|)*2^25 <= 3*2^52*2^25 < 2^79.
/// E: |d| <= 2*2^26*2^25 = 2^52. A: |d| <= 2^25.
using OffsetCoef = Int<79>;

/// 2x2 minor of two normals: 53+53 bits per product, +1 for the difference.
using NormalMinor = Int<107>;
static_assert(std::is_same_v<decltype(NormalCoef{} * NormalCoef{} - NormalCoef{} * NormalCoef{}), NormalMinor>,
              "normal minor: 53+53 = 106, difference -> 107");

/// 2x2 minor mixing a normal and an offset column: 53+79 = 132, difference -> 133.
using OffsetMinor = Int<133>;
static_assert(std::is_same_v<decltype(NormalCoef{} * OffsetCoef{} - NormalCoef{} * OffsetCoef{}), OffsetMinor>,
              "offset minor: 53+79 = 132, difference -> 133");

/// Homogeneous weight of the intersection of three arbitrary planes:
/// x4 = det of the three normals = sum of three (normal * normal minor):
/// 53+107 = 160 per term, three terms -> 162.
using PointW = Int<162>;

/// Homogeneous coordinates x1..x3: three terms of (normal * offset minor) or
/// (offset * normal minor): 53+133 = 79+107 = 186 per term, three terms -> 188.
using PointXYZ = Int<188>;

/// <point, plane> for a homogeneous point: x*a (188+53 = 241) and w*d
/// (162+79 = 241), four terms summed pairwise -> 243 <= 255.
using ClassifyValue = Int<243>;
static_assert(ClassifyValue::bits <= kMaxBits && PointXYZ::bits <= kMaxBits && PointW::bits <= kMaxBits,
              "points and classify must fit the core's 256-bit budget");

/// <p, n> + d for an integer point: 53+26 = 79 per product, three products ->
/// 81, + d (79) -> 82 bits: fits __int128.
using IntClassifyValue = Int<82>;
static_assert(IntClassifyValue::limbs == 2, "integer-point classify must fit __int128");

}  // namespace ember
