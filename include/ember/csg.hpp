#pragma once
// CSG expressions over operands, evaluated as ONE Boolean (docs/cpp-api.md, "Expressions").
//
//   const ember::Csg a = ember::Csg::operand(0), b = ember::Csg::operand(1), c = ember::Csg::operand(2);
//   ember::BooleanResult r = ember::boolean(meshes, (a | b) - c);
//
// An expression names operands by their index in the span passed to
// boolean(), so an operand used twice is read and quantized once. It becomes
// the indicator function over the winding-number vector; the early
// terminations follow from it mechanically (value_over), as for the built-in
// operations.
#include <cstddef>
#include <cstdint>
#include <initializer_list>
#include <span>
#include <string>
#include <vector>

#include "ember/boolean.hpp"

namespace ember {

/// An expression over operands 0, 1, ...: a value type (copies are cheap
/// enough for building expressions; evaluation never allocates for
/// expressions of up to 64 operand references).
class Csg {
 public:
  enum class Kind : unsigned char { Operand, Union, Intersection, Difference, Xor, AtLeast };

  /// Operand `index` of the span given to boolean().
  static Csg operand(std::size_t index);
  /// Inside at least k of the terms (k from 1 to terms.size()): the paper's
  /// k-of-n over any sub-expressions.
  static Csg at_least(int k, std::span<const Csg> terms);
  static Csg at_least(int k, std::initializer_list<Csg> terms) { return at_least(k, std::span(terms)); }
  /// A built-in operation over operands 0..n-1, as boolean(span, op) computes it.
  static Csg of(Operation op, std::size_t operands, int min_k = 1);

  friend Csg operator|(const Csg& a, const Csg& b);  ///< union
  friend Csg operator&(const Csg& a, const Csg& b);  ///< intersection
  friend Csg operator-(const Csg& a, const Csg& b);  ///< difference: in a and not in b
  friend Csg operator^(const Csg& a, const Csg& b);  ///< xor: in exactly one of a, b

  /// One more than the largest operand index used.
  std::size_t operand_count() const;
  /// Whether operand `index` appears in the expression.
  bool uses(std::size_t index) const;
  /// Inside the result at a point with winding numbers `w` (w_i != 0: inside operand i).
  bool inside(WindingVector w) const;
  /// The value over a set of points where operand i is known outside
  /// (state[i] == 0), known inside (1) or may be either (-1, independently per
  /// operand): 0 or 1 when every assignment gives that value, -1 when it may
  /// change. Never claims a constant wrongly; may answer -1 where an operand
  /// used twice would cancel (a ^ a).
  int value_over(std::span<const signed char> state) const;
  /// The expression in the CLI's syntax, with operands as "#i":
  /// "(#0 | #1) - #2"; every mix of operators is parenthesized.
  std::string to_string() const;

  /// The node list in postfix order (for the library's own evaluators).
  struct Node {
    Kind kind = Kind::Operand;
    std::uint32_t arity = 0;  ///< children (0 for an operand)
    std::uint32_t value = 0;  ///< the operand index, or k of AtLeast
  };
  std::span<const Node> nodes() const { return nodes_; }

 private:
  std::vector<Node> nodes_;    ///< postfix; the root is last
  std::size_t max_depth_ = 1;  ///< evaluation stack size
  static Csg combine(Kind kind, std::span<const Csg> terms, std::uint32_t value);
};

/// Evaluates `expression` over `operands` in one Boolean. Every operand must
/// be used by the expression (an unused one would still shape the common
/// grid), and the expression may use no operand beyond the span. The route
/// is chosen as for an operation (docs/cpp-api.md, "Expressions").
/// BooleanOptions::indicator and min_k must be left unset. Throws
/// ember::Error as boolean(operands, op) does.
BooleanResult boolean(std::span<const Mesh> operands, const Csg& expression, const BooleanOptions& options = {});

inline BooleanResult boolean(std::initializer_list<Mesh> operands, const Csg& expression,
                             const BooleanOptions& options = {}) {
  return boolean(std::span<const Mesh>(operands.begin(), operands.size()), expression, options);
}

}  // namespace ember
