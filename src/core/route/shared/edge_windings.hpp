#pragma once
// Winding numbers handed from a classified piece to its neighbour across a
// shared input edge, inside one leaf: a trace scans the whole leaf, so in a
// pile (thousands of long slivers that every box along them contains) one
// trace per piece is quadratic, while most pieces sit next to a piece of
// their own operand that is already classified.
//
// Why it is exact. Let piece f of polygon t and piece f' of t' (same operand)
// lie on the two sides of one input edge, run along it in opposite directions
// (consistently oriented) and share a segment s of positive length strictly
// inside the box. Near a point of s's interior the only sheets are t and t'
// unless some third polygon of the leaf contains a stretch of s's line:
//  * a polygon crossing s's line at one point x and entering t (or t') cuts f
//    (or f') there in the leaf's BSP, so x is an end of s, not inside it;
//  * one touching the line at one point without entering t or t' does not
//    disconnect the region between t and t' near s;
//  * one containing a stretch of the line (a third sheet through the edge, a
//    coplanar polygon reaching the edge) can: the receiver's `related` list
//    (gather: every polygon that touches t's plane near t) holds every such
//    polygon, and any of them but t' blocks the edge, unless it lies in t's
//    plane on t's side of the line or in t''s plane on t''s side (a twin of t
//    or t', as where two operands share a surface): near s such a polygon
//    covers part of t or t' itself and bounds the same two regions.
// So the region just in front of f and the one just in front of f' are one
// region near s, and so are the regions behind: every winding number that is
// constant along f' is the same along f. A solid operand's own polygons are
// not in `related` (they never cross t); they change only that operand's
// winding number, which is known (0 in front, 1 behind) on both sides anyway.
//
// Values come with a validity per operand and side: a piece that a leaf
// decided without cutting (the piece-level early termination) knows only the
// winding numbers of operands that are not free along that side of t (they
// are constant there); a piece the BSP refined knows them all.
#include <cstdint>
#include <span>
#include <vector>

#include "core/model/soup.hpp"
#include "core/route/shared/piece_edge_table.hpp"

namespace ember::core {

/// The polygons [begin, end) of a soup in an order in which each polygon but
/// the first of its group has an earlier one whose input triangle shares an
/// input edge with its own (breadth first over shared edges, from each
/// unvisited polygon in soup order). Solving in this order, a polygon's
/// neighbours across input edges are classified before it wherever they can
/// be, so EdgeWindings hands over to it instead of a trace.
std::vector<std::uint32_t> edge_neighbour_order(const Soup& soup, std::size_t begin, std::size_t end);

/// Whether a piece edge from -> to and a neighbour's piece edge n_from ->
/// n_to, both on the input edge a -> b's line, the neighbour's running the
/// other way (b -> a), share a stretch of positive length. Exact.
bool share_a_stretch(const IntPoint& a, const IntPoint& b, const Point& from, const Point& to, const Point& n_from,
                     const Point& n_to);

class EdgeWindings {
 public:
  /// `closed`: per operand, whether its surface is closed. An open operand's
  /// traced crossing count depends on the path (it changes around the
  /// surface's boundary), so it is never handed on.
  /// `expected_edges`: about how many piece edges on input edges the leaf
  /// will record (a sizing hint: the table and the entries are made that
  /// large once instead of growing by doubling and re-inserting).
  EdgeWindings(const std::vector<char>& closed, const Box& box, std::size_t expected_edges = 0);

  /// Starts the pieces of soup polygon `t` (not in a box face; materialized)
  /// whose gathered `related` polygons are given (soup indices).
  void begin_polygon(const Soup& soup, const SoupPolygon& t, std::span<const std::uint32_t> related);

  /// Winding numbers just in front of and behind piece f of the current
  /// polygon, from a recorded neighbour across one of f's input edges, if
  /// one is known for every operand o with need_front[o] (need_back[o]).
  /// `full` tells whether the values hold for all operands on both sides.
  bool find(const Polygon& f, std::span<const char> need_front, std::span<const char> need_back, Wnv& front, Wnv& back,
            bool& full);

  /// Records piece f of the current polygon as classified: front / back hold
  /// for every operand o with valid_front[o] (valid_back[o]).
  void record(const Polygon& f, const Wnv& front, const Wnv& back, std::span<const char> valid_front,
              std::span<const char> valid_back);

 private:
  /// Per input edge k of the current polygon.
  enum : std::uint8_t { kUnknown, kOpen, kBlocked };
  struct InputEdge {
    Plane plane;  ///< the triangle's edge plane (clip keeps it)
    std::uint8_t state = kUnknown;
    /// With kOpen: the related polygons containing a stretch of the line,
    /// except those lying on t's side in t's plane.
    std::vector<std::uint32_t> blockers;
  };

  /// Which of f's edges lie on input edge k of the current polygon.
  int input_edge_of(const Plane& edge) const;
  void classify_edge(int k);
  bool usable(const PieceEdgeTable::Entry& e, int k, const Point& from, const Point& to) const;
  /// Polygon o lies in `support` on the inner (negative) side of `edge`.
  bool on_inner_side(const SoupPolygon& o, const Plane& support, const Plane& edge) const;

  std::size_t operands_;
  std::vector<char> closed_;
  Box box_;
  const Soup* soup_ = nullptr;
  const SoupPolygon* t_ = nullptr;
  std::uint32_t t_index_ = 0;
  std::span<const std::uint32_t> related_;
  std::array<InputEdge, 3> edges_{};
  PieceEdgeTable table_;
  /// Per stored piece (PieceEdgeTable::windings): which front, then back values hold.
  std::vector<char> valid_;  ///< 2 * operands per stored piece
};

}  // namespace ember::core
