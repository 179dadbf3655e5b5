#pragma once
// Every failure the library can report reaches the caller as an ember::Error
// whose message says what was wrong and, where it applies, where (file, line or
// byte offset) and what to do about it. The library never prints.
//
// Where the problem is known to concern one operand, one file, one line, one
// face or one vertex, the error carries it as a field, so a caller that names
// operands differently (the CLI names them by file) composes its own message
// from problem() and the fields instead of parsing what().
#include <cstddef>
#include <optional>
#include <stdexcept>
#include <string>

namespace ember {

/// Where a problem lies, as far as it is known.
struct ErrorLocation {
  std::optional<std::size_t> operand;  ///< index into the Boolean's operands
  std::string file;                    ///< the file being read or written (empty: none)
  std::optional<std::size_t> line;     ///< 1-based line of a text file
  std::optional<std::size_t> face;     ///< face index within the operand or file
  std::optional<std::size_t> vertex;   ///< vertex index within the operand or file
};

class Error : public std::runtime_error {
 public:
  /// A message that stands alone (it names what it concerns itself).
  explicit Error(const std::string& message) : std::runtime_error(message), problem_(message) {}
  /// A problem at a location: what() is "operand i: problem" when the
  /// operand is known, else "file: problem" when the file is, else the problem.
  Error(std::string problem, ErrorLocation where)
      : std::runtime_error(compose(problem, where)), problem_(std::move(problem)), where_(std::move(where)) {}

  /// The message without the operand or file in front.
  const std::string& problem() const noexcept { return problem_; }
  const ErrorLocation& where() const noexcept { return where_; }
  std::optional<std::size_t> operand() const noexcept { return where_.operand; }

 private:
  static std::string compose(const std::string& problem, const ErrorLocation& where) {
    if (where.operand) return "operand " + std::to_string(*where.operand) + ": " + problem;
    if (!where.file.empty()) return where.file + ": " + problem;
    return problem;
  }
  std::string problem_;
  ErrorLocation where_;
};

}  // namespace ember
