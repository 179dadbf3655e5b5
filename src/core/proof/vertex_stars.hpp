#pragma once
// Embedded vertex stars: a certificate that lets the solid proof's contact
// search skip the exact test of neighbouring triangles (solid_proof.hpp,
// step 1).
//
// Most pairs of triangles whose boxes overlap share a vertex (a triangle
// meets about twelve neighbours that way), and giving each such pair the
// exact contact test would be most of the work. Instead, each vertex's star (every triangle of the
// operand with a corner there) is certified once, in O(valence):
//  * the triangles form one cycle t_0 .. t_{m-1} around v, t_i = (v, w_i,
//    w_{i+1}) counter-clockwise (indices mod m), consecutive ones sharing the
//    edge (v, w_{i+1});
//  * with d = the sum of their normals, every normal has n_t . d > 0, so the
//    projection along d is one-to-one and orientation-preserving on each
//    triangle: the projected triangles turn counter-clockwise around v, each
//    by an angle in (0, pi);
//  * the projected directions w_i - v wind around v exactly once.
// Then the projected triangles are sectors of one turn around v with
// disjoint interiors: two of them meet only in v's projection, or, when
// consecutive, along their common edge's projection. Each triangle being
// the one-to-one image of its projection, two triangles of the star meet
// only in v, or along their common edge: never improperly. A star that fails
// any condition (a non-manifold or folded vertex, a cone too sharp for one
// projection, a valence past kMaxValence) is not certified, and its pairs
// get the exact test as before.
//
// Winding once, exactly: take e_0 = w_0 - v as angle 0. A direction e is in
// the upper half (0, pi) iff d . (e_0 x e) > 0, else in the closed lower
// half [pi, 2 pi] (= 0: the projection is parallel to e_0's, at pi or at a
// full turn). Every step
// e_i -> e_{i+1} turns counter-clockwise by less than pi, so a step wraps
// past angle 0 (2 pi) exactly when it goes from the lower half to the upper
// one, and the last step back to e_0 always wraps: the winding number is
// 1 + (lower -> upper steps).
// Bits: normals < 2^53, so |d| < 2^63 for m <= 1024 and d . n < 2^118;
// e_0 x e < 2^53 (int64: differences < 2^26) and d . (e_0 x e) < 3 * 2^116,
// in __int128 (one 64 x 64 -> 128-bit product per term).
#include <span>

#include "core/model/grid_triangles.hpp"
#include "core/search/contact_triangle.hpp"

namespace ember::core {

/// Stars with more triangles are not certified (|d| must stay below 2^63).
inline constexpr std::size_t kMaxValence = 1024;

/// Sets ContactTriangle::embedded for `tris`, which must be *all* of an
/// operand's triangles (a star is every triangle at a vertex): bit k when
/// the star of corner k's vertex is certified. neighbours[i][k] is the
/// triangle across edge k of tris[i] (from corner k to corner k + 1) when
/// that edge is manifold (two uses, opposite directions:
/// GridTriangles::neighbors), as first_id + its index in tris, else
/// kNoNeighbor; ids outside tris count as none. The stars are walked
/// through these neighbours, O(valence) each. Deterministic, parallel
/// (oneTBB) in the caller's arena.
void certify_embedded_stars(std::span<ContactTriangle> tris, std::span<const std::array<std::uint32_t, 3>> neighbours,
                            std::uint32_t first_id = 0);

}  // namespace ember::core
