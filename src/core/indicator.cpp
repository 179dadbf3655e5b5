#include "core/indicator.hpp"

#include <string>
#include <vector>

#include "ember/error.hpp"

namespace ember {

namespace core {

bool inside_by_flags(Operation op, int min_k, std::span<const char> inside) {
  int count = 0;
  for (const char f : inside) count += f != 0;
  switch (op) {
    case Operation::Union:
      return count > 0;
    case Operation::Intersection:
      return count == static_cast<int>(inside.size());
    case Operation::Difference:
      return inside[0] != 0 && count == 1;
    case Operation::Xor:
      return count % 2 == 1;
    case Operation::AtLeastK:
      return count >= min_k;
  }
  return false;
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
    case Operation::Xor:
      break;
    case Operation::AtLeastK:
      if (min_k < 1 || static_cast<std::size_t>(min_k) > operands)
        throw Error("boolean: min_k must be between 1 and the number of operands (" + std::to_string(operands) +
                    "), got " + std::to_string(min_k));
      break;
    default:
      throw Error("boolean: unknown operation");
  }
  return [op, min_k](WindingVector w) {
    std::vector<char> flags(w.size());
    for (std::size_t i = 0; i < w.size(); ++i) flags[i] = w[i] != 0;
    return core::inside_by_flags(op, min_k, flags);
  };
}

}  // namespace ember
