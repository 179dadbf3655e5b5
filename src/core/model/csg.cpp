// CSG expressions (ember/csg.hpp): construction, two- and three-valued evaluation.
#include "ember/csg.hpp"

#include <algorithm>
#include <array>
#include <string>

#include "ember/error.hpp"

namespace ember {

namespace {

using Kind = Csg::Kind;
using Node = Csg::Node;

constexpr signed char kFree = -1;

/// One node over its children's values (0, 1 or kFree), in strong Kleene
/// logic: a value is claimed only when every assignment of the free children
/// gives it, which is what makes early terminations on it exact.
signed char combine_values(const Node& node, const signed char* v) {
  const std::uint32_t n = node.arity;
  std::uint32_t ones = 0, free = 0;
  for (std::uint32_t i = 0; i < n; ++i) {
    ones += v[i] == 1;
    free += v[i] == kFree;
  }
  switch (node.kind) {
    case Kind::Union: return ones > 0 ? 1 : (free > 0 ? kFree : 0);
    case Kind::Intersection: return ones == n ? 1 : (ones + free < n ? 0 : kFree);
    case Kind::Xor: return free > 0 ? kFree : static_cast<signed char>(ones % 2);
    case Kind::AtLeast: return ones >= node.value ? 1 : (ones + free < node.value ? 0 : kFree);
    case Kind::Difference: {
      // Inside the first child and outside every other.
      const std::uint32_t rest_ones = ones - (v[0] == 1), rest_free = free - (v[0] == kFree);
      if (v[0] == 0 || rest_ones > 0) return 0;
      return v[0] == 1 && rest_free == 0 ? 1 : kFree;
    }
    case Kind::Operand: break;
  }
  return kFree;
}

/// Evaluates the postfix program with `leaf(i)` as operand i's value. The
/// stack lives on the C++ stack for the usual sizes: the indicator runs once
/// per output piece, so it must not allocate.
template <class Leaf>
signed char evaluate(std::span<const Node> nodes, std::size_t depth, Leaf&& leaf) {
  std::array<signed char, 64> small{};
  std::vector<signed char> large;
  signed char* stack = small.data();
  if (depth > small.size()) {
    large.resize(depth);
    stack = large.data();
  }
  std::size_t top = 0;
  for (const Node& node : nodes) {
    if (node.kind == Kind::Operand) {
      stack[top++] = leaf(node.value);
      continue;
    }
    top -= node.arity;
    stack[top] = combine_values(node, stack + top);
    ++top;
  }
  return stack[0];
}

const char* symbol(Kind kind) {
  switch (kind) {
    case Kind::Union: return " | ";
    case Kind::Intersection: return " & ";
    case Kind::Difference: return " - ";
    case Kind::Xor: return " ^ ";
    default: return ", ";
  }
}

/// The subtree ending at node `end` (exclusive) as text; `begin` is set to its first node.
std::string text_of(std::span<const Node> nodes, std::size_t end, std::size_t& begin) {
  const Node& node = nodes[end - 1];
  if (node.kind == Kind::Operand) {
    begin = end - 1;
    return std::string(1, '#').append(std::to_string(node.value));
  }
  std::vector<std::string> parts(node.arity);
  std::size_t at = end - 1;
  for (std::uint32_t i = node.arity; i-- > 0;) {
    parts[i] = text_of(nodes, at, begin);
    const Node& child = nodes[at - 1];
    if (child.kind != Kind::Operand && child.kind != Kind::AtLeast) parts[i] = "(" + parts[i] + ")";
    at = begin;
  }
  begin = at;
  std::string out = node.kind == Kind::AtLeast ? "at_least(" + std::to_string(node.value) + ", " : "";
  for (std::uint32_t i = 0; i < node.arity; ++i) {
    if (i) out += symbol(node.kind);
    out += parts[i];
  }
  return node.kind == Kind::AtLeast ? out + ")" : out;
}

}  // namespace

Csg Csg::operand(std::size_t index) {
  if (index > 0xffffffffu) throw Error("Csg::operand: index " + std::to_string(index) + " is too large");
  Csg c;
  c.nodes_.push_back({Kind::Operand, 0, static_cast<std::uint32_t>(index)});
  return c;
}

Csg Csg::combine(Kind kind, std::span<const Csg> terms, std::uint32_t value) {
  Csg out;
  std::uint32_t arity = 0;
  std::size_t depth = 0;
  for (std::size_t t = 0; t < terms.size(); ++t) {
    const std::vector<Node>& in = terms[t].nodes_;
    if (in.empty()) throw Error("Csg: an empty expression (a default-constructed Csg) used as a term");
    // Associative operators absorb a child of the same kind (a | b) | c =
    // union(a, b, c); a difference absorbs its first term's difference
    // ((a - b) - c = a - b - c). One wide node keeps the tree shallow.
    const Node& root = in.back();
    const bool absorb =
        root.kind == kind && kind != Kind::AtLeast && kind != Kind::Operand && (kind != Kind::Difference || t == 0);
    out.nodes_.insert(out.nodes_.end(), in.begin(), absorb ? in.end() - 1 : in.end());
    depth = std::max(depth, arity + terms[t].max_depth_);
    arity += absorb ? root.arity : 1;
  }
  out.nodes_.push_back({kind, arity, value});
  out.max_depth_ = std::max<std::size_t>(depth, arity);
  return out;
}

Csg Csg::at_least(int k, std::span<const Csg> terms) {
  if (terms.empty()) throw Error("Csg::at_least: no terms given");
  if (k < 1 || static_cast<std::size_t>(k) > terms.size())
    throw Error("Csg::at_least: k must be between 1 and the number of terms (" + std::to_string(terms.size()) +
                "), got " + std::to_string(k));
  return combine(Kind::AtLeast, terms, static_cast<std::uint32_t>(k));
}

Csg Csg::of(Operation op, std::size_t operands, int min_k) {
  indicator_for(op, operands, min_k);  // the same checks as boolean(span, op)
  std::vector<Csg> terms;
  for (std::size_t i = 0; i < operands; ++i) terms.push_back(operand(i));
  if (operands == 1 && op != Operation::AtLeastK) return terms[0];
  switch (op) {
    case Operation::Union: return combine(Kind::Union, terms, 0);
    case Operation::Intersection: return combine(Kind::Intersection, terms, 0);
    case Operation::Difference: return combine(Kind::Difference, terms, 0);
    case Operation::Xor: return combine(Kind::Xor, terms, 0);
    case Operation::AtLeastK: return at_least(min_k, terms);
  }
  throw Error("Csg::of: unknown operation");
}

Csg operator|(const Csg& a, const Csg& b) { return Csg::combine(Csg::Kind::Union, std::array{a, b}, 0); }
Csg operator&(const Csg& a, const Csg& b) { return Csg::combine(Csg::Kind::Intersection, std::array{a, b}, 0); }
Csg operator-(const Csg& a, const Csg& b) { return Csg::combine(Csg::Kind::Difference, std::array{a, b}, 0); }
Csg operator^(const Csg& a, const Csg& b) { return Csg::combine(Csg::Kind::Xor, std::array{a, b}, 0); }

std::size_t Csg::operand_count() const {
  std::size_t n = 0;
  for (const Node& node : nodes_)
    if (node.kind == Kind::Operand) n = std::max<std::size_t>(n, node.value + std::size_t{1});
  return n;
}

bool Csg::uses(std::size_t index) const {
  return std::any_of(nodes_.begin(), nodes_.end(),
                     [&](const Node& node) { return node.kind == Kind::Operand && node.value == index; });
}

bool Csg::inside(WindingVector w) const {
  return evaluate(nodes_, max_depth_, [&](std::uint32_t i) -> signed char { return w[i] != 0 ? 1 : 0; }) == 1;
}

int Csg::value_over(std::span<const signed char> state) const {
  return evaluate(nodes_, max_depth_, [&](std::uint32_t i) { return state[i]; });
}

std::string Csg::to_string() const {
  if (nodes_.empty()) return "";
  std::size_t begin = 0;
  return text_of(nodes_, nodes_.size(), begin);
}

}  // namespace ember
