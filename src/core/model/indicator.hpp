#pragma once
// The built-in operations as functions of "inside operand i" flags (w_i != 0).
#include <span>

#include "ember/boolean.hpp"

namespace ember::core {

/// Every built-in operation depends only on how many of the `operands` contain
/// the point and on whether the first one does.
bool inside_by_count(Operation op, int min_k, std::size_t operands, std::size_t inside, bool first_inside);

/// Inside the result of `op` given per-operand inside flags.
inline bool inside_by_flags(Operation op, int min_k, std::span<const char> inside) {
  std::size_t count = 0;
  for (const char f : inside) count += f != 0;
  return inside_by_count(op, min_k, inside.size(), count, !inside.empty() && inside[0] != 0);
}

/// The value of `op` over a set of points where only some operands' inside
/// flags are known: of the `operands`, `inside` are known to contain the
/// points, `free` may or may not (independently), the rest do not. `first`
/// is operand 0's state: 1 inside, 0 outside, -1 free (counted in `free`).
/// Returns 0 or 1 when every assignment of the free flags gives that value,
/// -1 when the value can change. Exact for every built-in operation and
/// O(1), so early terminations need no enumeration and no operand limit.
int inside_over_free(Operation op, int min_k, std::size_t operands, std::size_t inside, std::size_t free, int first);

}  // namespace ember::core
