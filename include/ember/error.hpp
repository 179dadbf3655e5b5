#pragma once
// Every failure the library can report reaches the caller as an ember::Error
// whose message says what was wrong and, where it applies, where (file, line or
// byte offset) and what to do about it. The library never prints.
#include <stdexcept>
#include <string>

namespace ember {

class Error : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

}  // namespace ember
