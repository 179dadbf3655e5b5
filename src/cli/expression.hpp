#pragma once
// The expression of `ember eval`: mesh files combined with | & - ^ and
// parentheses (docs/cli.md, "Expressions").
#include <string>
#include <string_view>
#include <vector>

#include "ember/csg.hpp"

namespace ember::cli {

struct ParsedExpression {
  Csg expression;                  ///< over operands 0..paths.size()-1
  std::vector<std::string> paths;  ///< operand i is the file paths[i]; a path named twice is one operand
};

/// Parses `text`. Operators of one kind chain ("a | b | c", "a - b - c" is a
/// minus b minus c); mixing kinds needs parentheses, so no precedence rule
/// can surprise. A syntax error is a UsageError whose message names the
/// column and shows it under the expression.
ParsedExpression parse_expression(std::string_view text);

}  // namespace ember::cli
