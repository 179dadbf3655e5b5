#include "cli/expression.hpp"

#include <optional>

#include "cli/usage.hpp"

namespace ember::cli {

namespace {

/// Characters that end an unquoted file name. '-' does not: "my-part.stl" is
/// one name, and a difference needs the operator as a word of its own
/// ("a.obj - b.obj", or after a parenthesis).
bool ends_name(char c) {
  return c == ' ' || c == '\t' || c == '\n' || c == '|' || c == '&' || c == '^' || c == '(' || c == ')' || c == '\'' ||
         c == '"';
}

std::optional<Csg::Kind> operator_kind(char c) {
  switch (c) {
    case '|': return Csg::Kind::Union;
    case '&': return Csg::Kind::Intersection;
    case '-': return Csg::Kind::Difference;
    case '^': return Csg::Kind::Xor;
    default: return std::nullopt;
  }
}

class Parser {
 public:
  explicit Parser(std::string_view text) : text_(text) {}

  ParsedExpression parse() {
    Csg e = chain();
    skip_space();
    if (at_ < text_.size()) fail(text_[at_] == ')' ? "a ')' without its '('" : "an operator (| & - ^) expected");
    return {std::move(e), std::move(paths_)};
  }

 private:
  std::string_view text_;
  std::size_t at_ = 0;
  std::vector<std::string> paths_;

  [[noreturn]] void fail(const std::string& what, std::optional<std::size_t> column = std::nullopt) const {
    const std::size_t c = column.value_or(at_);
    throw UsageError("expression, column " + std::to_string(c + 1) + ": " + what + "\n  " + std::string(text_) +
                     "\n  " + std::string(c, ' ') + "^");
  }

  void skip_space() {
    while (at_ < text_.size() && (text_[at_] == ' ' || text_[at_] == '\t' || text_[at_] == '\n')) ++at_;
  }

  /// term (op term)*, all ops of one kind.
  Csg chain() {
    Csg e = term();
    std::optional<Csg::Kind> kind;
    std::size_t kind_column = 0;
    for (;;) {
      skip_space();
      if (at_ == text_.size() || text_[at_] == ')') return e;
      const std::optional<Csg::Kind> k = operator_kind(text_[at_]);
      if (!k)
        fail(
            "an operator (| & - ^) or the end expected after an operand (a '-' touching a name is part of it: "
            "write a - b)");
      if (kind && *k != *kind)
        fail(std::string{'\'', text_[at_], '\''}
                 .append(" after '")
                 .append(1, text_[kind_column])
                 .append("' without parentheses; operators of different kinds need parentheses, e.g. (a | b) - c"));
      kind = k;
      kind_column = at_++;
      const Csg rhs = term();
      switch (*k) {
        case Csg::Kind::Union: e = e | rhs; break;
        case Csg::Kind::Intersection: e = e & rhs; break;
        case Csg::Kind::Difference: e = e - rhs; break;
        default: e = e ^ rhs; break;
      }
    }
  }

  /// '(' chain ')' | a quoted or unquoted file name.
  Csg term() {
    skip_space();
    if (at_ == text_.size()) fail("a file name or '(' expected, but the expression ends");
    const char c = text_[at_];
    if (c == '(') {
      const std::size_t open = at_++;
      Csg e = chain();
      if (at_ == text_.size() || text_[at_] != ')') fail("this '(' is not closed", open);
      ++at_;
      return e;
    }
    if (c == '\'' || c == '"') return operand(quoted(c));
    if (ends_name(c) || operator_kind(c)) fail("a file name or '(' expected");
    const std::size_t begin = at_;
    while (at_ < text_.size() && !ends_name(text_[at_])) ++at_;
    return operand(std::string(text_.substr(begin, at_ - begin)));
  }

  std::string quoted(char quote) {
    const std::size_t open = at_++;
    const std::size_t close = text_.find(quote, at_);
    if (close == std::string_view::npos) fail("this quote is not closed", open);
    std::string name(text_.substr(at_, close - at_));
    if (name.empty()) fail("an empty file name", open);
    at_ = close + 1;
    return name;
  }

  Csg operand(std::string path) {
    for (std::size_t i = 0; i < paths_.size(); ++i)
      if (paths_[i] == path) return Csg::operand(i);
    paths_.push_back(std::move(path));
    return Csg::operand(paths_.size() - 1);
  }
};

}  // namespace

ParsedExpression parse_expression(std::string_view text) { return Parser(text).parse(); }

}  // namespace ember::cli
