#include "cli/usage.hpp"

#include <charconv>

namespace ember::cli {

int parse_int_option(const std::string& option, const std::string& text, long long lo, long long hi,
                     const std::string& range) {
  long long value = 0;
  const char* end = text.data() + text.size();
  const auto [ptr, ec] = std::from_chars(text.data(), end, value);
  if (ec == std::errc{} && ptr == end && value >= lo && value <= hi) return static_cast<int>(value);
  const bool number = ptr == end && (ec == std::errc{} || ec == std::errc::result_out_of_range) && !text.empty();
  throw UsageError(option + ": " +
                   (number ? "'" + text + "' is out of range" : "'" + text + "' is not a whole number") +
                   "; accepted: " + range);
}

std::uint64_t parse_count_option(const std::string& option, const std::string& text, const std::string& range) {
  std::uint64_t value = 0;
  const char* end = text.data() + text.size();
  const auto [ptr, ec] = std::from_chars(text.data(), end, value);
  if (ec == std::errc{} && ptr == end && value >= 1) return value;
  const bool number = ptr == end && !text.empty() && (ec == std::errc{} || ec == std::errc::result_out_of_range);
  throw UsageError(option + ": " +
                   (number ? "'" + text + "' is out of range" : "'" + text + "' is not a whole number") +
                   "; accepted: " + range);
}

}  // namespace ember::cli
