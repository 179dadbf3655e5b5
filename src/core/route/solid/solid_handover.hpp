#pragma once
// The solid path's winding numbers handed across shared input edges
// between pieces of touched triangles (solid_route.hpp, step 3): the leaves'
// EdgeWindings argument (edge_windings.hpp) for solid operands, where it
// simplifies. Pieces f of t and f' of t' (the two triangles of a manifold
// edge e of one solid operand) that share a stretch s of e of positive
// length see the same regions in front and behind near s, unless some other
// polygon contains a stretch of e's line: a polygon crossing e's line at one
// point and entering t or t' cuts f or f' there (so that point is an end of
// s), one touching the line without entering them does not disconnect the
// wedges between t and t', and t's operand has no third triangle at e.
// Every polygon that can contain a stretch of e meets t, so it is one of
// t's partners (solid_route.cpp); any partner whose plane holds e's line
// blocks the edge (conservative: the leaves let some twins pass), and so
// does an edge that is not manifold.
#include <array>
#include <cstdint>
#include <functional>
#include <span>
#include <vector>

#include "core/route/shared/pieces.hpp"
#include "core/model/soup.hpp"
#include "core/route/shared/piece_edge_table.hpp"
#include "core/model/grid_triangles.hpp"
#include "core/model/soup.hpp"

namespace ember::core {

class SolidHandover {
 public:
  explicit SolidHandover(std::size_t operands) : table_(operands) {}

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
  /// Which of t's edges, if any, the piece edge with plane `e` lies on.
  int input_edge_of(const Plane& e) const;
  bool blocked(int k);

  PieceEdgeTable table_;  ///< pieces by input edge; sources are triangle ids
  // The current triangle.
  std::uint32_t id_ = 0;
  const Polygon* t_ = nullptr;
  std::array<IntPoint, 3> c_{};
  std::array<std::uint32_t, 3> neighbours_{};
  std::span<const std::uint32_t> partners_;
  const GridTriangles* grid_ = nullptr;
  std::array<std::int8_t, 3> blocked_{};  ///< per edge: -1 unknown, 0 open, 1 blocked
};

/// Winding numbers handed between pieces of one touched triangle t across
/// the lines along which its partners' planes cut it (solid_route.hpp, step
/// 3). Pieces f and g of t that share a stretch s of positive length on the
/// cut line L of partner U (f's edge on U's plane, g's on its flip) see the
/// same regions beside s but for U's operand, which changes by one where s
/// lies in U. Why, with every operand solid:
///  * near a point of s off finitely many points, only t, U and polygons
///    whose planes hold L come close: any other polygon meeting s meets t,
///    so it is a partner, and a partner crossing L at a point cuts the
///    pieces there (that point ends s) unless its chord has no length, when
///    it touches s at isolated points only. A partner other than U whose
///    plane holds L (two points of s on it) blocks L; so does, to be safe, a
///    partner coplanar with t (its cuts are along its edges, not partners'
///    planes, and it lies in t's plane along s);
///  * s lies in U or beside it, never partly in it: an end p of U's chord
///    inside t lies on U's edge e, and the triangle across e (a partner,
///    crossing t's plane through p) cuts the pieces on its side of L at p,
///    so every shared stretch ends at p;
///  * where s lies in U (both ends in closed U), U's interior reaches both
///    sides of t near s (else U's edge would lie on L and U's neighbour
///    across it, holding L, would block it): going from g to f just in
///    front of t, or just behind, crosses U from g's side of U's plane to
///    f's, and U's operand's winding number drops by one from back to front
///    (its surface is outward).
/// t's own operand is 0 in front, 1 behind on every piece. Checked against
/// a trace for every derived piece of the benchmark's cases and of the core
/// tests (no difference), and
/// by the byte-identical outputs of tools/compare_builds.py.
/// Winding numbers of one triangle's pieces as they become known: per piece
/// its front, then its back values (`operands` each), and the order in which
/// they became known.
struct PieceWindings {
  std::size_t operands = 0;
  std::vector<int> w;
  std::vector<char> known;
  std::vector<std::uint32_t> order;

  /// `pieces` pieces, none known.
  void reset(std::size_t pieces, std::size_t operand_count);
  void store(std::size_t m, const Wnv& front, const Wnv& back);
  void get(std::size_t m, Wnv& front, Wnv& back) const;
  bool complete() const { return order.size() == known.size(); }
};

class CutHandover {
 public:
  /// Starts triangle t with its partners: their built polygons (`partner`)
  /// and operands (same order). None may be coplanar with t: a coplanar
  /// partner blocks every line, so the caller traces instead.
  void begin_triangle(const Polygon& t, std::span<const Polygon* const> partner,
                      std::span<const std::uint32_t> partner_operand);

  /// The cut line whose partner's plane is e (either orientation), or -1:
  /// e is t's input edge, not a partner's plane.
  int line_of(const Plane& e) const;

  /// f's winding numbers (front, back) from g's (g_front, g_back) across
  /// f's edge i and g's edge j, both on cut line `line`, if they run
  /// opposite ways, share a stretch of positive length and the line hands
  /// over.
  bool derive(const Polygon& f, std::size_t i, const Polygon& g, std::size_t j, int line, const Wnv& g_front,
              const Wnv& g_back, Wnv& front, Wnv& back);
  /// The same across any of f's edges on a cut line.
  bool derive(const Polygon& f, const Polygon& g, const Wnv& g_front, const Wnv& g_back, Wnv& front, Wnv& back);

  /// Completes `pw` for the current triangle's pieces, spreading from the
  /// known ones to their neighbours across cut lines (derive); when nothing
  /// known reaches the rest, trace(m, front, back) classifies the first of
  /// them (false: it found no path, and neither does spread) and the
  /// spreading goes on from it.
  bool spread(std::span<const Piece> pieces, PieceWindings& pw,
              const std::function<bool(std::size_t, Wnv&, Wnv&)>& trace);

 private:
  /// A transverse partner's cut line: found by its plane's normal (sign
  /// normalized), and whether it hands over (-1 not yet known, 0 open, 1
  /// blocked).
  struct Line {
    std::array<std::int64_t, 3> key;
    Plane plane;
    std::size_t partner = 0;
    std::int8_t state = -1;
  };
  /// Edge `edge` of piece `piece` lies on cut line `line`.
  struct CutEdge {
    std::uint32_t line, piece, edge;
  };
  /// Up to this many pieces, spreading tries every pair (no index to build).
  static constexpr std::size_t kFewPieces = 16;
  bool spread_among_few(std::span<const Piece> pieces, PieceWindings& pw,
                        const std::function<bool(std::size_t, Wnv&, Wnv&)>& trace);
  static std::array<std::int64_t, 3> key_of(const Plane& e);
  /// Decides whether a line hands over, from two distinct points on it.
  void decide(Line& line, const Point& p, const Point& q) const;

  const Polygon* t_ = nullptr;
  std::span<const Polygon* const> partner_;
  std::span<const std::uint32_t> operand_;
  std::vector<Line> lines_;                        ///< sorted by key
  std::vector<CutEdge> piece_edges_, line_edges_;  ///< the pieces' edges on cut lines, by piece / by line
  std::vector<std::uint32_t> piece_begin_;         ///< piece m's in piece_edges_
  Wnv g_front_, g_back_;
};

}  // namespace ember::core
