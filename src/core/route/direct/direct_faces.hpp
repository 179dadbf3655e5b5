#pragma once
// The direct route's work on one touched triangle (direct_mesh.hpp): its
// chords with its partners, joined into polylines and closed curves by the
// names of their end points, the faces they cut it into, and the kept
// faces' triangles.
#include <array>
#include <compare>
#include <cstdint>
#include <span>
#include <vector>

#include "core/output/output_vertices.hpp"
#include "core/output/region_triangulation.hpp"
#include "core/model/soup.hpp"
#include "core/model/grid_triangles.hpp"
#include "core/model/solve_context.hpp"

namespace ember::core {

/// A point where an edge of one operand crosses the interior of a triangle
/// of the other: the edge's welded vertex ids (smaller first) and the
/// crossed triangle's id.
struct CrossingName {
  std::uint64_t edge = 0;
  std::uint32_t face = 0;
  friend auto operator<=>(const CrossingName&, const CrossingName&) = default;
};

/// The point of segment a -> b (grid points) where it crosses a plane that
/// a and b lie strictly on opposite sides of, given their side values sa,
/// sb against it (grid_side: nonzero, |s| < 2^82): (a (-sb) + b sa) /
/// (sa - sb), with w > 0. Coordinates below 2^83 * 2^26 * 2 = 2^110 and w
/// below 2^84: well inside Point's bounds.
Point crossing_point(const IntPoint& a, const IntPoint& b, __int128 sa, __int128 sb);

/// Whether the crossing with side values (xa, xb) comes strictly before the
/// one with (ya, yb) along a common segment from its first point: its
/// parameter xa / (xa - xb) is smaller. Both pairs are of opposite signs.
bool crossing_before(__int128 xa, __int128 xb, __int128 ya, __int128 yb);

/// Where a touched triangle's work goes: per block of touched triangles,
/// their kept faces' triangles (corner refs: 0-2 the source triangle's
/// corners, 3 + i the block's crossing i), sources and crossings.
struct CutFaces {
  std::vector<CrossingName> names;
  std::vector<Point> points;
  std::vector<std::array<std::uint32_t, 3>> tris;
  std::vector<std::uint32_t> source;
  std::size_t faces = 0;
};

/// Vertex and edge names of the triangles of two operands: input vertex ids
/// (the operand's base plus its welded id), an edge as its two ids.
struct EdgeNames {
  const InputTopology& topo;
  std::span<const std::uint32_t> operand_of;
  std::uint32_t vertex(std::uint32_t t, int k) const {
    return topo.operand_base[operand_of[t]] + topo.by_triangle[t][static_cast<std::size_t>(k)];
  }
  std::uint64_t edge_key(std::uint32_t t, int k) const {
    const std::uint64_t u = vertex(t, k), v = vertex(t, k == 2 ? 0 : k + 1);
    return std::min(u, v) << 32 | std::max(u, v);
  }
};

/// An end point of the chord in which meeting triangles x and y cross: where
/// an edge of one crosses the other's interior. Its point is not stored
/// (120 bytes per chord end, for every meeting pair): each triangle that
/// has it computes it once (crossing_point).
struct ChordEnd {
  CrossingName name;
  __int128 sa = 0, sb = 0;  ///< the sides of its edge's end points against the other's plane
  std::uint8_t edge = 0;    ///< that edge (of y if on_y, else of x)
  bool on_y = false;
};

/// The chord of a meeting pair x < y, end[0] to end[1] in the direction
/// d = n_x x n_y: the inside of y's solid on its left, seen from x's front.
/// Seen from y, d is reversed (n_y x n_x), so the chord runs end[1] to end[0].
struct PairChord {
  std::array<ChordEnd, 2> end;
};

/// The chord of x < y (triangles of different operands whose closed sets
/// meet); false unless they meet in general position (no corner on the
/// other's plane, no edge meeting an edge of the other, one segment).
/// Each pair's chord is computed once and read by both triangles.
bool pair_chord(const GridTriangles& grid, const EdgeNames& names, std::uint32_t x, std::uint32_t y, PairChord& out);

/// A touched triangle's view of the chord of pair x < y: `reversed` when it
/// is y.
struct ChordRef {
  const PairChord* chord = nullptr;
  std::uint32_t x = 0, y = 0;
  bool reversed = false;
};

/// One touched triangle cut by its partners into faces; the kept faces'
/// triangles appended to a CutFaces.
class TriangleCutter {
 public:
  TriangleCutter(const GridTriangles& grid, const SolveContext& ctx, std::span<const std::uint32_t> operand_of)
      : grid_(grid), ctx_(ctx), operand_of_(operand_of) {
    front_.resize(2);
    back_.resize(2);
    local_.exact.resize(3);
  }

  /// False if the triangle is not in general position with its partners
  /// (or closed curves' nesting cannot be decided, or a face cannot be
  /// ear-clipped): the caller then declines the direct route.
  bool cut(std::uint32_t id, std::span<const ChordRef> chords, CutFaces& out) {
    cross_.clear();
    for (const ChordRef& r : chords) add_chord(r);
    if (!merge_equal_names()) return false;
    // Each point once per triangle, after the merge, in place among the
    // local vertices (0-2: the corners, set by walk_faces).
    local_.exact.resize(kCorners + cross_.size());
    for (std::size_t i = 0; i < cross_.size(); ++i) {
      const Crossing& x = cross_[i];
      const std::array<IntPoint, 3>& e = grid_.corners[x.tri];
      local_.exact[kCorners + i] = crossing_point(e[x.tri_edge], e[x.tri_edge == 2 ? 0 : x.tri_edge + 1], x.sa, x.sb);
    }
    for (const Crossing& x : cross_)
      if (x.edge >= 0 ? (x.next < 0) == (x.prev < 0) : (x.next < 0 || x.prev < 0)) return false;
    return walk_faces(id, grid_.corners[id], out);
  }

 private:
  /// A crossing point of one touched triangle, local to it.
  struct Crossing {
    CrossingName name;
    int edge = -1;              ///< the triangle's own edge it lies on, or -1 inside the triangle
    std::uint32_t tri = 0;      ///< the triangle whose edge it lies on (this one or the partner)
    std::uint8_t tri_edge = 0;  ///< that edge
    __int128 sa = 0, sb = 0;    ///< the sides of that edge's end points against the crossed plane
    int next = -1, prev = -1;   ///< chords: the crossing the curve runs on to / came from (local index)
  };

  /// Merges the chords' end points that have the same name (a crossing
  /// inside t ends two chords): one Crossing per name, in name order, with
  /// the chords' links. False if a crossing would get two successors or two
  /// predecessors (an edge shared by more than two triangles). A sort, not a
  /// search per end point: a large triangle may have thousands of partners.
  bool merge_equal_names();

  /// A chord's two end points as crossings of t, linked in t's direction
  /// (inside of the partner's solid on the left, seen from t's front).
  void add_chord(const ChordRef& r);

  /// Whether crossing x comes before crossing y along their common edge
  /// (from its first corner): x's parameter sa / (sa - sb) is smaller.
  bool before(const Crossing& x, const Crossing& y) const;

  /// A face of t: its outer loop (counter-clockwise, local ids), holes
  /// (clockwise) and the other operand's winding number on it (-1: not yet known).
  struct Face {
    std::vector<std::uint32_t> loop;
    std::vector<std::vector<std::uint32_t>> holes;
    int w = -1;
    /// Records w = value; false if the face already had the other value.
    bool agree(bool value) {
      if (w >= 0 && w != static_cast<int>(value)) return false;
      w = value;
      return true;
    }
  };
  Face& next_face() {
    if (faces_.size() == face_count_) faces_.emplace_back();
    Face& f = faces_[face_count_++];
    f.loop.clear(), f.holes.clear(), f.w = -1;
    return f;
  }

  /// The faces of t between its boundary and the polylines, each walked
  /// counter-clockwise; the kept ones ear-clipped into `out`.
  bool walk_faces(std::uint32_t id, const std::array<IntPoint, 3>& c, CutFaces& out);
  /// The curves that close inside t: a face inside each, a hole in the face around it.
  bool add_closed_curves(const Plane& support);
  /// The kept faces' triangles, appended to `out` (crossing i is name_base + i there).
  bool emit_faces(std::uint32_t id, const Plane& support, std::uint32_t name_base, CutFaces& out);

  static constexpr std::uint32_t kCorners = 3;  ///< local ids: 0-2 t's corners, 3 + i crossing i

  const GridTriangles& grid_;
  const SolveContext& ctx_;
  std::span<const std::uint32_t> operand_of_;
  std::vector<Crossing> cross_, merged_;
  std::vector<std::uint32_t> order_, merged_at_;
  // Scratch: the boundary ring (local ids: 0-2 corners, 3 + i crossing i),
  // per crossing its ring slot, a face's loop, its triangles.
  std::vector<std::uint32_t> ring_, slot_;
  std::vector<char> arc_used_, visited_;
  std::vector<Face> faces_;  ///< the first face_count_ are this triangle's (reused storage)
  std::size_t face_count_ = 0;
  std::vector<std::vector<std::uint32_t>> loops_;
  std::vector<std::array<std::uint32_t, 3>> tris_;
  OutputVertices local_;
  Wnv front_, back_;
};

}  // namespace ember::core
