#pragma once
// The --stats line: one flat JSON object on stderr (string and number values
// only, so that simple tools can read it).
#include <string>
#include <vector>

#include "ember/boolean.hpp"

namespace ember::cli {

/// Prints the stats of a Boolean; `inputs` names the operands.
void print_stats(const BooleanResult& r, const char* operation, const std::vector<std::string>& inputs);

}  // namespace ember::cli
