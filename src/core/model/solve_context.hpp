#pragma once
// What every route is told about the Boolean: the indicator and what is known of the operands.
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <optional>
#include <vector>

#include "core/model/indicator.hpp"
#include "core/model/soup.hpp"
#include "ember/csg.hpp"

namespace ember::core {

/// How the result crosses a surface piece (SolveContext::crossing).
struct Crossing {
  bool emitted = false;         ///< the piece is on the result's surface
  bool flip = false;            ///< emitted reversed: the result lies in front of it
  std::uint8_t lo = 0, hi = 0;  ///< layer mode: the layers it bounds (OutputPolygon::layer_lo, layer_hi)
};

struct SolveContext {
  std::size_t operands = 0;
  std::function<bool(const Wnv&)> inside;  ///< indicator: WNV -> inside the result
  /// The built-in operation behind `inside` (empty for a custom indicator).
  /// Every built-in operation depends only on "inside operand i" flags
  /// (w_i != 0); knowing which one lets early terminations decide exactly
  /// whether unknown flags can change the result (`over_free`).
  std::optional<Operation> op;
  int min_k = 1;
  /// The expression behind `inside` when it is one (ember/csg.hpp): its
  /// three-valued evaluation (`Csg::value_over`) gives the early
  /// terminations what `over_free` gives a built-in operation.
  const Csg* expression = nullptr;
  /// Layer mode (ember::boolean_layers): every piece where the count of
  /// operands containing the point changes is emitted, with the layers it
  /// bounds, so one solve gives every "inside at least k" layer. No early
  /// termination applies (op and expression are unset).
  bool layers = false;
  /// Per operand: closed (every directed edge matched by an opposite one), so
  /// its winding number changes only across its surface. Lets the leaf skip
  /// cuts along coplanar polygons' edges (see docs/design.md).
  std::vector<char> closed;
  /// Per operand: solid (closed, outward, no self-intersections, no nested or
  /// touching components: w in {0, 1}). Enables the shortcuts of Fig. 11.
  std::vector<char> solid;
  std::size_t leaf_size =
      256;  ///< subdivide while a subproblem has more polygons (tuned: docs/design.md "Subdivision")
  /// Leaves hand winding numbers across shared input edges instead of
  /// tracing every piece (edge_windings.hpp). Off only in tests that compare
  /// the two.
  bool share_edge_windings = true;

  /// inside_over_free for the built-in operation; -1 (may change) for a
  /// custom indicator.
  int over_free(std::size_t inside_count, std::size_t free, int first) const {
    return op ? inside_over_free(*op, min_k, operands, inside_count, free, first) : -1;
  }

  /// The result's crossing of a piece with winding numbers `front` and
  /// `back` on its two sides.
  Crossing crossing(const Wnv& front, const Wnv& back) const {
    if (layers) {
      std::size_t f = 0, b = 0;
      for (std::size_t i = 0; i < front.size(); ++i) {
        f += front[i] != 0;
        b += back[i] != 0;
      }
      return {f != b, f > b, static_cast<std::uint8_t>(std::min(f, b)), static_cast<std::uint8_t>(std::max(f, b))};
    }
    const bool in_front = inside(front), in_back = inside(back);
    return {in_front != in_back, in_front, 0, 0};
  }
};

}  // namespace ember::core
