#include "core/model/indicator.hpp"

#include <string>

#include "ember/error.hpp"

namespace ember {

namespace core {

bool inside_by_count(Operation op, int min_k, std::size_t operands, std::size_t inside, bool first_inside) {
  switch (op) {
    case Operation::Union: return inside > 0;
    case Operation::Intersection: return inside == operands;
    case Operation::Difference: return first_inside && inside == 1;
    case Operation::Xor: return inside % 2 == 1;
    case Operation::AtLeastK: return inside >= static_cast<std::size_t>(min_k);
  }
  return false;
}

int inside_over_free(Operation op, int min_k, std::size_t operands, std::size_t inside, std::size_t free, int first) {
  if (free == 0) return inside_by_count(op, min_k, operands, inside, first == 1) ? 1 : 0;
  switch (op) {
    case Operation::Union:  // count >= 1
      return inside > 0 ? 1 : -1;
    case Operation::Intersection:  // count == operands
      return inside + free < operands ? 0 : -1;
    case Operation::Xor:  // every free flag flips the parity
      return -1;
    case Operation::AtLeastK:  // count >= k
      if (inside >= static_cast<std::size_t>(min_k)) return 1;
      return inside + free < static_cast<std::size_t>(min_k) ? 0 : -1;
    case Operation::Difference:  // operand 0 inside and no other
      if (first == 0) return 0;
      if (first == 1) return inside >= 2 ? 0 : -1;  // a free other may be inside or not
      return inside >= 1 ? 0 : -1;                  // operand 0 free: only known others decide
  }
  return -1;
}

}  // namespace core

// A point is inside operand i when its winding number w_i is non-zero (the
// paper's convention: nested and inverted shells count as inside).
Indicator indicator_for(Operation op, std::size_t operands, int min_k) {
  if (operands == 0) throw Error("boolean: no operands given; pass at least one mesh");
  switch (op) {
    case Operation::Union:
    case Operation::Intersection:
    case Operation::Difference:
    case Operation::Xor: break;
    case Operation::AtLeastK:
      if (min_k < 1 || static_cast<std::size_t>(min_k) > operands)
        throw Error("boolean: min_k must be between 1 and the number of operands (" + std::to_string(operands) +
                    "), got " + std::to_string(min_k));
      break;
    default: throw Error("boolean: unknown operation");
  }
  // Counting in place keeps the per-piece indicator call allocation-free.
  return [op, min_k](WindingVector w) {
    std::size_t count = 0;
    for (const int x : w) count += x != 0;
    return core::inside_by_count(op, min_k, w.size(), count, !w.empty() && w[0] != 0);
  };
}

}  // namespace ember
