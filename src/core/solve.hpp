#pragma once
// The recursive EMBER solver: adaptive subdivision with reference-point
// propagation (Section 4.2) down to leaves that resolve intersections with
// polygon-local BSPs (4.3) and classify pieces by segment tracing (4.4).
#include <functional>
#include <optional>
#include <vector>

#include "core/indicator.hpp"
#include "core/soup.hpp"

namespace ember::core {

/// A piece of an input polygon that lies on the result's surface.
struct OutputPolygon {
  /// Support plane and vertices; no edge planes (the mesh stage decides
  /// incidences on the vertices). Only the support plane when `corners` is
  /// set: an input triangle that an early-out or a leaf emitted unbuilt
  /// (soup.hpp), or that merge_whole_triangles put back together; its corners
  /// are grid points, which the mesh stage welds by their coordinates.
  Polygon poly;
  std::uint32_t id = 0;       ///< source polygon (input triangle) id
  std::uint32_t operand = 0;
  bool flip = false;          ///< emit with reversed orientation (in-out transition)
  /// The polygon is the whole subdivision piece its source triangle had in
  /// the box that emitted it (no leaf cut or trimmed it), and that piece was
  /// made by `splits` subdivision splits (SoupPolygon::splits).
  bool whole_piece = false;
  std::uint8_t splits = 0;
  const std::array<IntPoint, 3>* corners = nullptr;  ///< set iff unbuilt (GridTriangles::corners[id])
};

/// How many corners p has (3 for an unbuilt triangle).
inline std::size_t corner_count(const OutputPolygon& p) { return p.corners ? 3 : p.poly.vertices.size(); }

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
  std::size_t leaf_size = 64;  ///< subdivide while a subproblem has more polygons (tuned: docs/benchmark.md)

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
  Soup soup;
  Dyadic ref;
  Wnv ref_w;
};

/// Early termination (Section 4.5.2): true when every winding-number vector
/// reachable inside the subproblem maps to the same side of the indicator,
/// so it cannot contribute output. Operands without polygons in the
/// subproblem keep the reference point's winding number.
bool indicator_constant(const Subproblem& problem, const SolveContext& ctx);

/// Solves a subproblem; output polygons come in a deterministic order that
/// does not depend on scheduling.
std::vector<OutputPolygon> solve(Subproblem&& problem, const SolveContext& ctx);

/// Winding-number vectors just in front of and behind polygon t of pb's soup
/// (the whole polygon, which must not be crossed or overlapped by any other
/// polygon of the soup), traced from pb's reference point. False if no valid
/// path was found.
bool classify_polygon(const Subproblem& problem, const SoupPolygon& t, Wnv& w_front, Wnv& w_back);

/// Leaf computation (exposed for tests).
void solve_leaf(const Subproblem& problem, const SolveContext& ctx, std::vector<OutputPolygon>& out);

}  // namespace ember::core
