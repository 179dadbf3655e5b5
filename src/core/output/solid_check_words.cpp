// Words for the per-operand report (ember/boolean.hpp), shared by the
// library's warnings and the CLI's --stats.
#include <string>

#include "ember/boolean.hpp"

namespace ember {

bool self_intersection_count_is_lower_bound(const OperandReport& r) {
  return !r.self_intersecting_pairs_complete || r.self_intersecting_pairs >= OperandReport::kMaxReportedPairs;
}

std::string describe_solid_check(const OperandReport& r) {
  switch (r.solid) {
    case SolidStatus::NotChecked: return "not checked";
    case SolidStatus::Promised: return "solid (promised, not checked)";
    case SolidStatus::Proven: return "proven solid";
    case SolidStatus::Open:
      return "not solid: open (" + std::to_string(r.open_edges) + " edges not matched by an opposite edge)";
    case SolidStatus::SelfIntersecting: {
      return "not solid: self-intersecting (" +
             std::string(self_intersection_count_is_lower_bound(r) ? "at least " : "") +
             std::to_string(r.self_intersecting_pairs) + " triangle pairs meet beyond a shared vertex or edge)";
    }
    case SolidStatus::Misoriented:
      return "not solid: inconsistent orientation (" + std::to_string(r.misoriented_components) +
             " components are inverted or nested: winding number not 0 in front of their faces)";
    case SolidStatus::Undecided:
      return "not proven solid (touching slivers or too many components for the proof's budget)";
  }
  return "?";
}

}  // namespace ember
