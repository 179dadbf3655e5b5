#pragma once
// Exact proof that an operand is *solid* in the sense the core's shortcuts
// need (paper Section 4.5.1, NSI + NNC; BooleanOptions::solid): its winding
// number is 0 in front of and 1 behind every one of its triangles.
//
// The proof has three exact steps on the quantized, non-degenerate triangles:
//  1. no self-intersection: any two triangles meet in nothing, a shared
//     vertex, or a shared edge (integer orientation predicates, <= 84 bits);
//  2. components: triangles joined across manifold edges (used once in each
//     direction). By step 1 nothing else comes near such an edge, so the
//     winding number in front of a component is one constant;
//  3. one classification trace per component gives that constant: it must be
//     0 (and 1 behind).
// Every doubt (touching, T-junctions, non-manifold edges, too many
// components for the trace budget, a failed trace) answers "not solid": the
// caller then takes the general path, which is always correct.
#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <span>

#include "core/support/fill_vector.hpp"
#include "core/route/general/solve.hpp"
#include "core/search/triangle_tree.hpp"
#include "geometry/bounds.hpp"

namespace ember::core {

class LeafDiagonals;
class RootProblem;
struct OperandTrees;

enum class SolidVerdict {
  Solid,
  SelfIntersecting,   ///< two triangles meet beyond a shared vertex or edge (or touch)
  WrongWinding,       ///< some component has winding != 0 in front (nested, inverted)
  TooComplex,         ///< beyond the proof's work budget (many components, piles of slivers): not decided
  Unclassified,       ///< no valid trace path (not decided)
};

inline constexpr std::uint32_t kNoNeighbor = UINT32_MAX;

/// The grid triangles behind the soup's polygons, indexed by polygon id.
/// FillVectors (fill_vector.hpp): build_grid_triangles sizes them, then writes every
/// entry in parallel.
struct GridTriangles {
  FillVector<std::array<IntPoint, 3>> corners;
  /// grid_normal of each triangle's corners (non-zero: degenerate
  /// triangles are not kept), stored for the hot loops that need it (the
  /// proof's contact tests, the partner search, the pair chords): 24 bytes
  /// per triangle against recomputing it in each (~6 M of the bunny pair's
  /// 250 M instructions).
  FillVector<std::array<std::int64_t, 3>> normals;
  /// Welded vertex ids (edge_matching.hpp): within one operand, equal ids iff equal positions.
  FillVector<std::array<std::uint32_t, 3>> vertex_ids;
  /// Bit k: edge k is a manifold edge of its operand (EdgeMatching::manifold).
  FillVector<std::uint8_t> manifold_edges;
  /// Across manifold edge k: the other triangle's id (kNoNeighbor: none, or
  /// the edge is not manifold, or the other triangle is degenerate).
  FillVector<std::array<std::uint32_t, 3>> neighbors;
};

/// Components of the triangles with keep[i], joined across their manifold
/// edges (GridTriangles::neighbors, both ends kept): per kept triangle the
/// smallest id of its component (other entries unspecified). Shared by the
/// proof's components and the solid path's untouched ones.
FillVector<std::uint32_t> neighbour_components(const GridTriangles& grid, std::span<const char> keep);
/// The same for all triangles first .. first + count - 1 (an operand's range
/// of ids) and the manifold edges between them: entry i is triangle first +
/// i's. Linear in count, not in all triangles.
FillVector<std::uint32_t> neighbour_components(const GridTriangles& grid, std::uint32_t first, std::size_t count);

/// The verdict and, for the user, how much evidence was found against it.
struct SolidFinding {
  SolidVerdict verdict = SolidVerdict::Solid;
  std::size_t self_intersecting_pairs = 0;  ///< counted up to OperandReport::kMaxReportedPairs
  std::size_t misoriented_components = 0;
  bool pairs_complete = true;  ///< self_intersecting_pairs is every pair (ContactSearchResult::complete)
};

/// Decides whether `operand` is solid. `root` is the whole problem (its
/// triangles are grid's, polygon i is triangle i; its reference point is
/// outside everything); its soup is built (RootProblem::with_soup) only where
/// a scan of it is needed: a proof without `trees`, or a trace through the
/// tree that found no non-degenerate path.
/// `trees`, if given, are the operands' triangle trees with their leaves'
/// extents (build_operand_trees over root.operand_begin()).
/// `intersecting`, if given, is set as soon as the search meets the first
/// self-intersection, before the count is complete: the defaults' solid
/// path, started alongside the proof on the premise that every operand is
/// solid, stops on it (solve_solid's `abandon`) and frees its threads.
SolidFinding check_solid(RootProblem& root, const GridTriangles& grid, std::uint32_t operand,
                         const OperandTrees* trees = nullptr, std::atomic<bool>* intersecting = nullptr);

/// A grid triangle prepared for the contact test: where its corners are,
/// their welded ids (equal iff equal positions, within the triangles
/// compared) and its normal (p1 - p0) x (p2 - p0) (grid_normal), computed
/// once per triangle instead of once per pair.
/// The corners are referred to, not copied: the proof holds one entry per
/// triangle of the operand it proves, and a copy (72 bytes) made the entry
/// 112 bytes: 61 MB per operand of the 1.08M-triangle union (26 MB now),
/// and at 16 threads both operands are proven at once (docs/redesign.md,
/// session 21). The caller keeps the corners alive (the proof: GridTriangles::corners).
struct ContactTriangle {
  const std::array<IntPoint, 3>* corners = nullptr;
  std::array<std::int64_t, 3> n;
  std::array<std::uint32_t, 3> id;
  /// Bit k: the star of corner k's vertex is certified embedded
  /// (vertex_stars.hpp), so triangles sharing that vertex never meet
  /// improperly. 0 (nothing certified) unless certify_embedded_stars set it.
  std::uint8_t embedded = 0;
  const std::array<IntPoint, 3>& p() const { return *corners; }
};
static_assert(sizeof(ContactTriangle) <= 48, "ContactTriangle: the proof's per-triangle entry");
/// The contact triangle of the corners `p`, which must outlive it.
ContactTriangle contact_triangle(const std::array<IntPoint, 3>& p, const std::array<std::uint32_t, 3>& ids);
/// The same with p's grid normal given (GridTriangles::normals).
inline ContactTriangle contact_triangle(const std::array<IntPoint, 3>& p, const std::array<std::int64_t, 3>& n,
                                        const std::array<std::uint32_t, 3>& ids) {
  return {&p, n, ids, 0};
}
/// The triangle points at `p`: a temporary would dangle.
ContactTriangle contact_triangle(std::array<IntPoint, 3>&& p, const std::array<std::uint32_t, 3>& ids) = delete;

/// A triangle's extent along D directions: lowest projections, then highest
/// (diagonal_extent; frame_extent in leaf_frame_extents.hpp).
template <std::size_t D>
struct ProjectedExtent {
  std::array<std::int64_t, D> lo, hi;
};

/// The two extents do not overlap along some direction. Where each bounds
/// its triangle's projections (exactly, or widened), the triangles are
/// disjoint: a common point would project into both.
template <std::size_t D>
bool extents_apart(const ProjectedExtent<D>& a, const ProjectedExtent<D>& b) {
  for (std::size_t k = 0; k < D; ++k)
    if (a.hi[k] < b.lo[k] || b.hi[k] < a.lo[k]) return true;
  return false;
}

/// A triangle's extent along the four diagonals (1,1,1), (1,1,-1), (1,-1,1),
/// (-1,1,1). With the box it bounds the triangle by 14 planes; long slivers
/// across the axes, whose boxes overlap many others', are told apart by it.
using DiagonalExtent = ProjectedExtent<4>;
inline DiagonalExtent diagonal_extent(const std::array<IntPoint, 3>& p) {
  // |coordinate| <= 2^25: a projection is below 3 * 2^25 in magnitude.
  static_assert(3 * kCoordLimit < (std::int64_t{1} << 62), "diagonal projections must fit int64");
  const auto project = [](const IntPoint& q) {
    const std::int64_t s = q.x + q.y, d = q.x - q.y;
    return std::array<std::int64_t, 4>{s + q.z, s - q.z, d + q.z, q.z - d};
  };
  const std::array<std::int64_t, 4> a = project(p[0]), b = project(p[1]), c = project(p[2]);
  DiagonalExtent e;
  for (int k = 0; k < 4; ++k) {
    e.lo[k] = std::min({a[k], b[k], c[k]});
    e.hi[k] = std::max({a[k], b[k], c[k]});
  }
  return e;
}

/// The two extents do not overlap along some diagonal: the triangles are
/// disjoint (exact: integer projections), so they do not meet at all.
inline bool diagonally_apart(const DiagonalExtent& a, const DiagonalExtent& b) { return extents_apart(a, b); }

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
  bool strictly_one_side() const {
    return (s[0] > 0 && s[1] > 0 && s[2] > 0) || (s[0] < 0 && s[1] < 0 && s[2] < 0);
  }
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
