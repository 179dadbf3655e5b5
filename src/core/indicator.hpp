#pragma once
// The built-in operations as functions of "inside operand i" flags (w_i != 0).
#include <span>

#include "ember/boolean.hpp"

namespace ember::core {

/// Inside the result of `op` given per-operand inside flags.
bool inside_by_flags(Operation op, int min_k, std::span<const char> inside);

}  // namespace ember::core
