#pragma once
// The chords of a leaf's C3 test (leaf.cpp, cut_by_transverse): where two
// polygons on crossing planes meet the other's plane. A piece is cut when
// the two chords overlap with positive length; the exact answer
// (line_region_has_length over chord_constraints) costs thousands of
// instructions, and most pairs that reach it do not overlap at all.
#include <cstdint>
#include <vector>

#include "geometry/geometry.hpp"

namespace ember::core {

/// Appends the edges of a convex polygon that can bound the chord where a
/// line in the plane `cut` crosses it: edges whose end points lie on opposite
/// sides of `cut` or touch it (`signs`: the vertices' exact sides of `cut`).
/// The other edges contain the whole chord.
void chord_constraints(const Polygon& poly, const std::vector<std::int8_t>& signs, std::vector<Plane>& out);

enum class ChordOverlap { kYes, kNo, kUnsure };

/// The cheap answers to "do the chord of `a` along `sb` and the chord of `b`
/// along `sa` overlap with positive length?", before the exact test:
///  * kYes when double estimates of both chords overlap by clearly more than
///    their rounding error (2^-10 grid units against errors near 2^-26 for
///    well-shaped input). It may err: a superfluous cut refines the piece's
///    partition without changing any classification;
///  * kNo when chords_surely_disjoint says so (never wrong);
///  * kUnsure otherwise: the caller decides exactly.
ChordOverlap filter_chords(const Polygon& a, const Plane& sa, const std::vector<std::int8_t>& signs_a, const Polygon& b,
                           const Plane& sb, const std::vector<std::int8_t>& signs_b);

/// True only if the chord of polygon `a` (on plane `sa`) along plane `sb` and
/// the chord of polygon `b` (on `sb`) along `sa` are certainly disjoint: then
/// they cannot overlap with positive length and no cut is needed. `signs_a`
/// are a's vertices' exact sides of `sb`, `signs_b` b's of `sa`. A
/// floating-point filter with rigorous bounds (chords.cpp): false whenever it
/// cannot be sure, never true when the chords meet.
bool chords_surely_disjoint(const Polygon& a, const Plane& sa, const std::vector<std::int8_t>& signs_a,
                            const Polygon& b, const Plane& sb, const std::vector<std::int8_t>& signs_b);

/// Exact and cheap, for chords that touch end to end: true if an edge
/// plane of `a` has all of `b` on its non-negative side. For `a` with
/// vertices strictly on both sides of b's plane (what the C3 test asks
/// about), the two chords then share at most one point and do not overlap
/// with positive length. The common case in a closed mesh: a piece of a
/// triangle t whose edge was cut along a partner q's plane ends on the line
/// exactly where the edge that q shares with b crosses t, and b lies beyond
/// q's plane. False says nothing.
bool chords_separated_by_edge(const Polygon& a, const Polygon& b);

}  // namespace ember::core
