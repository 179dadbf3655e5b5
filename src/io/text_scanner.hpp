#pragma once
// Shared by the text readers (OBJ, OFF, ASCII PLY, ASCII STL): a cursor over
// the file bytes that tracks the line number, parses numbers with
// std::from_chars without allocating, and formats errors as "name:line: what".
// Binary readers use fail_at_offset for "name: byte N: what".
#include <charconv>
#include <cmath>
#include <cstring>
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

namespace ember::io_detail {

[[noreturn]] void fail_at_line(std::string_view name, std::size_t line, std::string_view what);
[[noreturn]] void fail_at_offset(std::string_view name, std::size_t offset, std::string_view what);
[[noreturn]] void fail_in_file(std::string_view name, std::string_view what);
/// A short printable rendering of untrusted bytes for messages ('abc', '\x07').
std::string quote(std::string_view bytes);

class TextScanner {
 public:
  /// In multiline mode blanks include newlines and '#' comments, so values may
  /// spread over lines (OFF, PLY, STL); otherwise the scanner stays on the
  /// current line and a '#' ends it (OBJ).
  TextScanner(std::string_view text, std::string_view name, bool multiline, char comment)
      : begin_(text.data()),
        p_(text.data()),
        end_(text.data() + text.size()),
        name_(name),
        multiline_(multiline),
        comment_(comment) {}

  [[noreturn]] void fail(std::string_view what) const { fail_at_line(name_, line_, what); }
  std::size_t line() const { return line_; }
  std::string_view name() const { return name_; }
  std::size_t remaining() const { return static_cast<std::size_t>(end_ - p_); }
  const char* position() const { return p_; }

  /// Skips blanks (see constructor) and backslash-newline continuations.
  void skip_blanks() {
    for (;;) {
      while (p_ != end_ && (*p_ == ' ' || *p_ == '\t' || *p_ == '\r' || *p_ == '\f' || *p_ == '\v')) ++p_;
      if (p_ == end_) return;
      const char c = *p_;
      if (c == '\\' && continuation()) continue;
      if (!multiline_) return;
      if (c == '\n') {
        ++p_;
        ++line_;
      } else if (c == comment_ && comment_ != 0) {
        skip_rest_of_line();
      } else {
        return;
      }
    }
  }
  /// True at end of data, end of line or a comment (single-line mode).
  bool at_line_end() {
    skip_blanks();
    return p_ == end_ || *p_ == '\n' || (comment_ != 0 && *p_ == comment_);
  }
  /// True if the current line has another value (multiline mode: newlines
  /// and comments are not crossed).
  bool more_on_line() {
    for (;;) {
      while (p_ != end_ && (*p_ == ' ' || *p_ == '\t' || *p_ == '\r' || *p_ == '\f' || *p_ == '\v')) ++p_;
      if (p_ == end_ || *p_ != '\\' || !continuation()) break;
    }
    return p_ != end_ && *p_ != '\n' && !(comment_ != 0 && *p_ == comment_);
  }
  bool at_end() {
    skip_blanks();
    return p_ == end_;
  }
  /// Moves past the next newline (or to the end) and counts it.
  void next_line() {
    skip_rest_of_line();
    if (p_ != end_) {
      ++p_;
      ++line_;
    }
  }
  /// The next run of non-blank bytes; empty at the end of the line/data.
  std::string_view token() {
    if (at_line_end()) return {};
    const char* s = p_;
    while (p_ != end_ && !is_space(*p_)) ++p_;
    return {s, static_cast<std::size_t>(p_ - s)};
  }
  /// A finite floating-point value; `what` names it in errors. With
  /// finite_only false, nan and inf are accepted (for values that are skipped).
  double real(std::string_view what, bool finite_only = true) {
    const char* s = start_value(what);
    double v = 0;
    auto [q, ec] = std::from_chars(s, end_, v);
    if (ec == std::errc::result_out_of_range) fail_bad_value(s, what, " is out of range");
    if (ec != std::errc() || !ends_value(q, 0)) fail_bad_value(s, what, " is not a number");
    if (finite_only && !std::isfinite(v)) fail_bad_value(s, what, " is not finite");
    p_ = q;
    return v;
  }
  /// An integer; `stop` is an extra byte allowed right after it (OBJ's '/').
  std::int64_t integer(std::string_view what, char stop = 0) {
    const char* s = start_value(what);
    std::int64_t v = 0;
    auto [q, ec] = std::from_chars(s, end_, v);
    if (ec == std::errc::result_out_of_range) fail_bad_value(s, what, " is out of range");
    if (ec != std::errc() || !ends_value(q, stop)) fail_bad_value(s, what, " is not an integer");
    p_ = q;
    return v;
  }
  /// Moves back or forward within the current line (e.g. to re-read the part
  /// of a token that was glued to a keyword).
  void set_position(const char* p) { p_ = p; }
  /// Skips the rest of a token (e.g. the "/vt/vn" after an OBJ vertex index).
  void skip_token_rest() {
    while (p_ != end_ && !is_space(*p_)) ++p_;
  }
  /// The rest of the current token, consumed (empty right after a token ends).
  std::string_view token_rest() {
    const char* s = p_;
    skip_token_rest();
    return {s, static_cast<std::size_t>(p_ - s)};
  }
  /// Consumes `s` if the next token starts with it exactly.
  bool accept(std::string_view s) {
    skip_blanks();
    if (static_cast<std::size_t>(end_ - p_) < s.size() || std::string_view(p_, s.size()) != s) return false;
    const char* q = p_ + s.size();
    if (q != end_ && !is_space(*q)) return false;
    p_ = q;
    return true;
  }

  static bool is_space(char c) { return c == ' ' || c == '\t' || c == '\n' || c == '\r' || c == '\f' || c == '\v'; }

 private:
  bool continuation() {
    const char* q = p_ + 1;
    if (q != end_ && *q == '\r') ++q;
    if (q == end_ || *q != '\n') return false;
    p_ = q + 1;
    ++line_;
    return true;
  }
  void skip_rest_of_line() {
    const void* nl = std::memchr(p_, '\n', static_cast<std::size_t>(end_ - p_));
    p_ = nl ? static_cast<const char*>(nl) : end_;
  }
  const char* start_value(std::string_view what) {
    if (at_line_end())
      fail(std::string("expected ").append(what).append(p_ == end_ ? ", found end of file" : ", found end of line"));
    // from_chars rejects a leading '+', which some exporters write.
    if (*p_ == '+' && p_ + 1 != end_ && *(p_ + 1) != '-' && *(p_ + 1) != '+') ++p_;
    return p_;
  }
  bool ends_value(const char* q, char stop) const {
    return q == end_ || is_space(*q) || (comment_ != 0 && *q == comment_) || (stop != 0 && *q == stop);
  }
  [[noreturn]] void fail_bad_value(const char* s, std::string_view what, std::string_view why) const {
    const char* e = s;
    while (e != end_ && !is_space(*e) && e - s < 40) ++e;
    fail(std::string(what).append(" ").append(quote({s, static_cast<std::size_t>(e - s)})).append(why));
  }

  const char* begin_;
  const char* p_;
  const char* end_;
  std::string_view name_;
  std::size_t line_ = 1;
  bool multiline_;
  char comment_;
};

/// The text without a leading UTF-8 byte-order mark (some Windows tools write
/// one before the header; it carries no information for these formats).
inline std::string_view skip_bom(std::string_view text) {
  if (text.starts_with("\xEF\xBB\xBF")) text.remove_prefix(3);
  return text;
}

}  // namespace ember::io_detail
