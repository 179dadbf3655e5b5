#pragma once
// Option values the CLI checks itself, so that every usage error names the
// option and the accepted range (and exits with 2).
#include <cstdint>
#include <stdexcept>
#include <string>

namespace ember::cli {

/// A usage error: main() prints it and exits with status 2.
struct UsageError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

/// Parses a whole number in [lo, hi] given for `option`; `range` describes
/// the accepted values for the message ("0 = all cores, or more").
int parse_int_option(const std::string& option, const std::string& text, long long lo, long long hi,
                     const std::string& range);
/// Parses a whole number from 1 to 2^64-1 given for `option`.
std::uint64_t parse_count_option(const std::string& option, const std::string& text, const std::string& range);

}  // namespace ember::cli
