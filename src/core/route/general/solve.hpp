#pragma once
// The recursive EMBER solver: adaptive subdivision with reference-point
// propagation (Section 4.2) down to leaves that resolve intersections with
// polygon-local BSPs (4.3) and classify pieces by segment tracing (4.4).
#include <functional>
#include <memory>
#include <optional>
#include <vector>

#include "core/model/indicator.hpp"
#include "core/model/soup.hpp"

namespace ember::core {

/// The splits that made a subproblem's box, as a chain from the subproblem
/// up to the root (null: the root's box). Shared by a subproblem's children,
/// immutable, so that an output piece can name its box by its chunk's path.
struct SplitStep {
  std::shared_ptr<const SplitStep> parent;
  std::int64_t position = 0;
  int axis = 0;
  bool upper = false;  ///< the subproblem lies above the split plane
};
using SplitPath = std::shared_ptr<const SplitStep>;

/// A piece of an input triangle that lies on the result's surface, in one of
/// three forms (48 bytes; most output pieces are the first two):
///  * unbuilt: the whole input triangle (`corners`), emitted by an early-out
///    or a leaf that did not cut it, or put back together by
///    merge_whole_triangles;
///  * by path (`path` set): the triangle's whole subdivision piece in the
///    box that emitted it, i.e. the triangle clipped by that box's splits in
///    their order (expand_path_pieces rebuilds it exactly). Most such pieces
///    merge back into whole triangles, so their vertices are never stored;
///  * explicit: the vertices of a piece a leaf cut or trimmed.
/// The support plane is always the triangle's (support_of).
struct OutputPolygon {
  PolygonBuffer<Point> vertices;  ///< explicit corners (counter-clockwise around the support); else empty
  const std::array<IntPoint, 3>* corners = nullptr;  ///< the source triangle's grid corners (GridTriangles::corners[id])
  std::uint32_t id = 0;       ///< source polygon (input triangle) id
  std::uint32_t operand = 0;
  /// By path: an index into the solve's paths (SolveOutput); kNoPath otherwise.
  std::uint32_t path = kNoPath;
  /// How many subdivision splits made the piece (SoupPolygon::splits).
  std::uint8_t splits = 0;
  bool flip = false;          ///< emit with reversed orientation (in-out transition)
  /// The polygon is the whole subdivision piece its source triangle had in
  /// the box that emitted it (no leaf cut or trimmed it).
  bool whole_piece = false;
  /// Nothing else in the output can touch it but along its own edges and at
  /// its corners: an unbuilt triangle whose three edges it shares with whole
  /// triangles of its operand that no other operand comes near (the solid
  /// path's interior triangles, solid_route.hpp). No vertex lies inside its
  /// edges and none of its corners inside another polygon's edge, so the
  /// mesh stage passes it through as it is.
  bool settled = false;

  static constexpr std::uint32_t kNoPath = UINT32_MAX;
};

/// The whole input triangle, without stored vertices.
inline bool unbuilt(const OutputPolygon& p) { return p.vertices.empty() && p.path == OutputPolygon::kNoPath; }
/// How many corners p has (3 for an unbuilt triangle; a path piece must be expanded first).
inline std::size_t corner_count(const OutputPolygon& p) { return unbuilt(p) ? 3 : p.vertices.size(); }
/// The support plane of p: its input triangle's.
inline Plane support_of(const OutputPolygon& p) {
  const std::array<IntPoint, 3>& c = *p.corners;
  return *supporting_plane(c[0], c[1], c[2]);  // an output triangle has area
}

struct SolveContext {
  std::size_t operands = 0;
  std::function<bool(const Wnv&)> inside;  ///< indicator: WNV -> inside the result
  /// The built-in operation behind `inside` (empty for a custom indicator).
  /// Every built-in operation depends only on "inside operand i" flags
  /// (w_i != 0); knowing which one lets early terminations decide exactly
  /// whether unknown flags can change the result (`over_free`).
  std::optional<Operation> op;
  int min_k = 1;
  /// Per operand: closed (every directed edge matched by an opposite one), so
  /// its winding number changes only across its surface. Lets the leaf skip
  /// cuts along coplanar polygons' edges (see docs/core.md).
  std::vector<char> closed;
  /// Per operand: solid (closed, outward, no self-intersections, no nested or
  /// touching components: w in {0, 1}). Enables the shortcuts of Fig. 11.
  std::vector<char> solid;
  std::size_t leaf_size = 256;  ///< subdivide while a subproblem has more polygons (tuned: docs/core.md "Subdivision")
  /// Leaves hand winding numbers across shared input edges instead of
  /// tracing every piece (edge_windings.hpp). Off only in tests that compare
  /// the two.
  bool share_edge_windings = true;

  /// inside_over_free for the built-in operation; -1 (may change) for a
  /// custom indicator.
  int over_free(std::size_t inside_count, std::size_t free, int first) const {
    return op ? inside_over_free(*op, min_k, operands, inside_count, free, first) : -1;
  }
};

/// A self-contained subproblem: polygons clipped to a closed integer box and a
/// reference point strictly inside the box with its winding-number vector.
struct Subproblem {
  Box box;
  SplitPath path;  ///< the splits that made `box` (null at the root)
  Soup soup;
  Dyadic ref;
  Wnv ref_w;
};

/// Early termination (Section 4.5.2): true when every winding-number vector
/// reachable inside the subproblem maps to the same side of the indicator,
/// so it cannot contribute output. Operands without polygons in the
/// subproblem keep the reference point's winding number.
bool indicator_constant(const Subproblem& problem, const SolveContext& ctx);

/// Whether splitting `polygons` polygons, `straddling` of which land in both
/// children, is worth it, or the subproblem is a pile better solved as one
/// leaf (subdivide.cpp). A pile leaf's work grows about as the square of its
/// size (each polygon meets every polygon whose box meets its own), so the
/// split pays only while two children of (n + s) / 2 polygons cost less than
/// one leaf of n: (n + s)^2 < 2 n^2, that is s < (sqrt 2 - 1) n ~ 0.41 n.
/// (With 3/4 of the polygons allowed to straddle, the sliver pile's leaves
/// held 294,802 polygon copies of its 31,360 triangles.)
bool split_pays(std::size_t polygons, std::size_t straddling);

/// What solve() emits: output polygons in a deterministic order that does not
/// depend on scheduling, and the paths their path pieces refer to.
struct SolveOutput {
  std::vector<OutputPolygon> polys;
  std::vector<SplitPath> paths;
};

/// Solves a subproblem.
SolveOutput solve(Subproblem&& problem, const SolveContext& ctx);

/// Winding-number vectors just in front of and behind polygon t of pb's soup
/// (the whole polygon, which must not be crossed or overlapped by any other
/// polygon of the soup), traced from pb's reference point. False if no valid
/// path was found.
bool classify_polygon(const Subproblem& problem, const SoupPolygon& t, Wnv& w_front, Wnv& w_back);

/// The output form of soup polygon p, a whole subdivision piece: unbuilt if no
/// split cut its triangle, else by path (path 0: the emitting subproblem's,
/// which solve() numbers).
OutputPolygon whole_piece_output(const SoupPolygon& p, bool flip);

/// Leaf computation (exposed for tests). Path pieces carry path 0.
void solve_leaf(const Subproblem& problem, const SolveContext& ctx, std::vector<OutputPolygon>& out);

}  // namespace ember::core
