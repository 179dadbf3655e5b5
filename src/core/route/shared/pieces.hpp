#pragma once
// The polygon-local BSP of one polygon t (paper Section 4.3) and the choice
// of a classification target inside each of its pieces (Section 4.4), shared
// by the leaves of the subdivision (leaf.cpp) and the solid path
// (solid_route.hpp), which differ only in where t's neighbours and the
// winding numbers come from.
#include <cstdint>
#include <vector>

#include "core/model/soup.hpp"
#include "core/route/shared/trace.hpp"

namespace ember::core {

/// A convex piece of a polygon (a leaf of the paper's local BSP).
struct Piece {
  Polygon poly;
};

/// Coplanar convex polygons overlap with positive area iff no edge of either
/// weakly separates them (separating-axis theorem in the common plane).
bool coplanar_overlap(const Polygon& a, const Polygon& b);

/// Case C4 for a coplanar polygon with a higher id: cut piece i along the
/// edges of `other`; parts outside become new pieces. `neg`, `pos` are
/// scratch (a cut piece's old buffers serve the next clip).
void cut_by_coplanar(std::vector<Piece>& pieces, std::size_t i, const Polygon& other, Polygon& neg, Polygon& pos);

/// Which sides of a plane a polygon's vertices lie on.
struct Sides {
  bool below = false, above = false;
  int on = 0;  ///< vertices on the plane
  bool straddles() const { return below && above; }
};
/// The sides of `signs` (each -1, 0 or +1).
Sides sides_of(const std::vector<std::int8_t>& signs);
/// poly's vertices against `plane`, exactly (behind classify's filter), into
/// `signs`; the plane is converted to doubles once, not per vertex.
Sides classify_vertices(const Polygon& poly, const Plane& plane, std::vector<std::int8_t>& signs);

/// Whether the chord where `other`'s plane crosses `poly` (on `support`;
/// `signs`: poly's vertices against other's plane, strictly on both sides)
/// and the chord where `support` crosses `other` (`other_signs`) overlap
/// with positive length: filter_chords, then the exact test. `cons` is
/// scratch. The test of split_by_transverse, which pile leaves' gather
/// also asks (leaf.cpp).
bool chords_overlap(const Polygon& poly, const Plane& support, const std::vector<std::int8_t>& signs,
                    const Polygon& other, const std::vector<std::int8_t>& other_signs, std::vector<Plane>& cons);

/// Case C3 for one polygon: true if the other polygon's plane splits `poly`
/// (on `support`), i.e. their intersection segment crosses poly's interior
/// with positive length; then the halves are in `neg` and `pos`.
/// `other_signs` are the other polygon's vertices classified against
/// `support`; `signs` and `cons` are scratch.
bool split_by_transverse(const Polygon& poly, const Plane& support, const Polygon& other,
                         const std::vector<std::int8_t>& other_signs, std::vector<std::int8_t>& signs,
                         std::vector<Plane>& cons, Polygon& neg, Polygon& pos);

/// Case C3 in place: piece i becomes the negative half, the positive half a
/// new piece at the end. `neg`, `pos` are scratch (a cut piece's old buffers
/// serve the next clip).
void cut_by_transverse(std::vector<Piece>& pieces, std::size_t i, const Plane& support, const Polygon& other,
                       const std::vector<std::int8_t>& other_signs, std::vector<std::int8_t>& signs,
                       std::vector<Plane>& cons, Polygon& neg, Polygon& pos);

/// Classifies o's vertices against a plane into `signs`; false if all lie
/// strictly on one side (o cannot meet the plane).
bool touches_plane(const Polygon& o, const Plane& plane, const PlaneApprox& approx, std::vector<std::int8_t>& signs);
/// The same for a triangle's grid corners (its built polygon's vertices, in
/// order), exactly in 82-bit integers.
bool touches_plane(const std::array<IntPoint, 3>& corners, const Plane& plane, std::vector<std::int8_t>& signs);

/// One polygon p of operand `operand` met by the last segment `seg` of a
/// classification path, which ends at x on plane S (x strictly inside a
/// piece on S): a polygon in S containing x adds its transition to `delta`
/// (signed relative to S's orientation), any other adds its crossing to w.
/// False when the meeting is degenerate (x on p's boundary, or the segment
/// touching p at an edge, a vertex or its end).
bool meet_onto(const AxisSegment& seg, const Polygon& p, std::uint32_t operand, const Plane& S, const AxisPoint& x,
               Wnv& w, Wnv& delta);

/// The last segment of a classification path: along axis k from dyadic
/// `start` onto x, a point of plane S on start's axis line. `side` is the
/// side of S the segment comes from. False if start lies on S.
bool onto_segment(const Plane& S, const Dyadic& start, int k, const AxisPoint& x, AxisSegment& seg, int& side);

/// Calls try_target(target, x, variant) for dyadic targets whose axis-k line
/// (k = dominant axis of f's plane) meets f strictly inside, at x, until it
/// returns true; false if none did. target has `base`'s coordinate k and a
/// shift >= base.shift. Guesses come from double approximations first (the
/// centroid, then `seed`ed convex combinations, variant 0 / 1 alternating),
/// then exact centroids of vertex triples (each tried with both variants),
/// which find slivers far thinner than a double resolves.
template <typename Try>
bool for_each_interior_target(const Polygon& f, const Dyadic& base, std::uint64_t seed, Try&& try_target);

namespace piece_targets {
std::uint64_t mix(std::uint64_t x);
/// The interior guess of attempt `attempt`: (coordinate i, coordinate j).
std::array<double, 2> interior_guess(const Polygon& f, int i, int j, int attempt, std::uint64_t seed);
/// The exact centroid of f's vertices a, a+1, a+2 on axes i, j, snapped to 2^-shift.
void exact_centroid(const Polygon& f, std::size_t a, int i, int j, Dyadic& target);
/// Where the axis-k line through target meets f's plane, if strictly inside f.
bool interior_point(const Polygon& f, const Dyadic& target, int k, AxisPoint& x);
}  // namespace piece_targets

template <typename Try>
bool for_each_interior_target(const Polygon& f, const Dyadic& base, std::uint64_t seed, Try&& try_target) {
  const int k = dominant_axis(f.support);
  const int i = (k + 1) % 3, j = (k + 2) % 3;
  for (int attempt = 0; attempt < 24; ++attempt) {
    const std::array<double, 2> c = piece_targets::interior_guess(f, i, j, attempt, seed);
    // Snap to the coarsest dyadic grid whose point still lies strictly inside.
    for (int s = 7 + attempt / 4; s <= kMaxDyadicShift; ++s) {
      Dyadic target = with_shift(base, std::max(s, base.shift));
      const double scale = static_cast<double>(std::int64_t{1} << target.shift);  // exact power of two
      target.num[i] = static_cast<__int128>(std::nearbyint(c[0] * scale));
      target.num[j] = static_cast<__int128>(std::nearbyint(c[1] * scale));
      AxisPoint x;
      if (!piece_targets::interior_point(f, target, k, x)) continue;
      if (try_target(target, x, attempt % 2)) return true;
      break;  // inside but the path is degenerate: next guess
    }
  }
  for (std::size_t a = 0; a < f.vertices.size(); ++a) {
    for (int s = 7; s <= kMaxDyadicShift; s += 3) {  // 7, 10, ..., 52
      Dyadic target = with_shift(base, std::max(s, base.shift));
      piece_targets::exact_centroid(f, a, i, j, target);
      AxisPoint x;
      if (!piece_targets::interior_point(f, target, k, x)) continue;
      for (const int variant : {0, 1})
        if (try_target(target, x, variant)) return true;
    }
  }
  return false;
}

}  // namespace ember::core
