#include "io/text_scanner.hpp"

#include <cstdio>

#include "ember/error.hpp"

namespace ember::io_detail {

void fail_at_line(std::string_view name, std::size_t line, std::string_view what) {
  throw Error(std::string(name) + ":" + std::to_string(line) + ": " + std::string(what));
}

void fail_at_offset(std::string_view name, std::size_t offset, std::string_view what) {
  throw Error(std::string(name) + ": byte " + std::to_string(offset) + ": " + std::string(what));
}

void fail_in_file(std::string_view name, std::string_view what) {
  throw Error(std::string(name) + ": " + std::string(what));
}

std::string quote(std::string_view bytes) {
  std::string out = "'";
  const std::size_t limit = 40;
  for (std::size_t i = 0; i < bytes.size() && i < limit; ++i) {
    const auto c = static_cast<unsigned char>(bytes[i]);
    if (c >= 0x20 && c < 0x7f && c != '\'' && c != '\\') {
      out += static_cast<char>(c);
    } else {
      char buf[8];
      std::snprintf(buf, sizeof buf, "\\x%02x", c);
      out += buf;
    }
  }
  if (bytes.size() > limit) out += "...";
  return out + "'";
}

}  // namespace ember::io_detail
