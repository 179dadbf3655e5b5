#include <string>

#include "ember/boolean.hpp"
#include "ember/error.hpp"

namespace ember {

// A point is inside operand i when its winding number w_i is non-zero (the
// paper's convention: nested and inverted shells count as inside).
Indicator indicator_for(Operation op, std::size_t operands, int min_k) {
  if (operands == 0) throw Error("boolean: no operands given; pass at least one mesh");
  switch (op) {
    case Operation::Union:
      return [](WindingVector w) {
        for (const int x : w)
          if (x != 0) return true;
        return false;
      };
    case Operation::Intersection:
      return [](WindingVector w) {
        for (const int x : w)
          if (x == 0) return false;
        return true;
      };
    case Operation::Difference:
      return [](WindingVector w) {
        if (w[0] == 0) return false;
        for (std::size_t i = 1; i < w.size(); ++i)
          if (w[i] != 0) return false;
        return true;
      };
    case Operation::Xor:
      return [](WindingVector w) {
        int count = 0;
        for (const int x : w) count += x != 0;
        return count % 2 == 1;
      };
    case Operation::AtLeastK:
      if (min_k < 1 || static_cast<std::size_t>(min_k) > operands)
        throw Error("boolean: min_k must be between 1 and the number of operands (" + std::to_string(operands) +
                    "), got " + std::to_string(min_k));
      return [min_k](WindingVector w) {
        int count = 0;
        for (const int x : w) count += x != 0;
        return count >= min_k;
      };
  }
  throw Error("boolean: unknown operation");
}

}  // namespace ember
