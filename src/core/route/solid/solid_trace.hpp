#pragma once
// Classification traces of the solid path (solid_route.hpp, step 3): the
// paper's segment traces (Sections 3.4, 4.4) with the polygons a segment can
// meet found through the operands' triangle trees instead of a leaf's soup.
//
// A piece f of a triangle of solid operand `own` needs the winding numbers
// of the other operands just in front of and behind it (own's are 0 and 1):
// traced from outside the root box, where every winding number is 0, along
// f's dominant axis k onto a point strictly inside f, the nearer face of the
// box first. (Local references near the pieces, as the leaves have, were
// tried: the three-segment paths from them crossed more triangles' boxes
// than the one straight segment from outside.)
#include <vector>

#include "core/search/operand_trees.hpp"
#include "core/model/soup.hpp"

namespace ember::core {

/// What every trace reads.
struct Tracer {
  std::span<const std::array<IntPoint, 3>> corners;  ///< the grid triangles by id (GridTriangles::corners)
  const OperandTrees& trees;
  const Box& box;  ///< the root box: no polygon touches its boundary
  std::size_t operands;
};

/// Scratch of one worker.
struct TraceScratch {
  Wnv w, delta;
  Polygon built;  ///< an unbuilt triangle met by a trace
};

/// Winding numbers just in front of and behind piece f (on its triangle's
/// plane) of a triangle of solid operand `own`, traced from outside the root
/// box. False if every path tried met something degenerately.
bool classify_from_outside(const Tracer& tr, const Polygon& f, std::uint32_t own, std::uint64_t seed, Wnv& w_front,
                           Wnv& w_back, TraceScratch& sc);

/// Operand `own`'s winding numbers just in front of and behind piece f (on
/// its triangle's plane), from own's triangles alone: `tree` over them (item
/// i is grid triangle first + i, with corners corners[first + i]; f's
/// triangle among them), traced from outside the root box as above. The
/// solid proof's check that a component of own faces outwards
/// (solid_proof.hpp): one tree query instead of scans of the whole soup.
/// False if every path tried met something degenerately.
bool own_winding_from_outside(std::span<const std::array<IntPoint, 3>> corners, const TriangleTree& tree,
                              std::uint32_t first, const Box& box, std::size_t operands, const Polygon& f,
                              std::uint32_t own, std::uint64_t seed, int& front, int& back, TraceScratch& sc);

}  // namespace ember::core
