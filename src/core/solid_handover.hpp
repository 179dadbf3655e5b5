#pragma once
// The solid path's winding numbers handed across shared input edges
// between pieces of touched triangles (solid_path.hpp, step 3): the leaves'
// EdgeWindings argument (edge_windings.hpp) for solid operands, where it
// simplifies. Pieces f of t and f' of t' (the two triangles of a manifold
// edge e of one solid operand) that share a stretch s of e of positive
// length see the same regions in front and behind near s, unless some other
// polygon contains a stretch of e's line: a polygon crossing e's line at one
// point and entering t or t' cuts f or f' there (so that point is an end of
// s), one touching the line without entering them does not disconnect the
// wedges between t and t', and t's operand has no third triangle at e.
// Every polygon that can contain a stretch of e meets t, so it is one of
// t's partners (solid_path.cpp); any partner whose plane holds e's line
// blocks the edge (conservative: the leaves let some twins pass), and so
// does an edge that is not manifold.
#include <span>
#include <vector>

#include "core/soup.hpp"
#include "core/solid_check.hpp"

namespace ember::core {

class SolidHandover {
 public:
  explicit SolidHandover(std::size_t operands) : operands_(operands) {}

  /// Forgets every recorded piece (buffers are kept).
  void clear();

  /// Starts the pieces of triangle `id` (built polygon `t`) with its
  /// partners (ids of other operands' triangles meeting it).
  void begin_triangle(std::uint32_t id, const Polygon& t, std::span<const std::uint32_t> partners,
                      const GridTriangles& grid);

  /// Winding numbers of piece f of the current triangle from a recorded
  /// piece of a neighbour across a shared stretch of an input edge.
  bool find(const Polygon& f, Wnv& front, Wnv& back);

  /// Records piece f of the current triangle as classified.
  void record(const Polygon& f, const Wnv& front, const Wnv& back);

 private:
  struct Entry {
    Point from, to;             ///< the piece's edge on the input edge, in its own direction
    IntPoint a, b;              ///< the input edge, in the piece's direction
    std::uint32_t tri = 0;      ///< the piece's triangle
    std::uint32_t winding = 0;  ///< front at 2 * operands * winding in windings_, then back
    std::uint32_t next = UINT32_MAX;  ///< next entry in the same hash slot
  };
  static std::size_t hash(const IntPoint& a, const IntPoint& b);
  std::uint32_t& slot(const IntPoint& a, const IntPoint& b);
  /// Which of t's edges, if any, the piece edge with plane `e` lies on.
  int input_edge_of(const Plane& e) const;
  bool blocked(int k);

  std::size_t operands_;
  std::vector<Entry> entries_;
  std::vector<std::uint32_t> slots_ = std::vector<std::uint32_t>(1024, UINT32_MAX);  ///< chains by hash of (a, b)
  std::vector<int> windings_;
  // The current triangle.
  std::uint32_t id_ = 0;
  const Polygon* t_ = nullptr;
  std::array<IntPoint, 3> c_{};
  std::array<std::uint32_t, 3> neighbours_{};
  std::span<const std::uint32_t> partners_;
  const GridTriangles* grid_ = nullptr;
  std::array<std::int8_t, 3> blocked_{};  ///< per edge: -1 unknown, 0 open, 1 blocked
};

}  // namespace ember::core
