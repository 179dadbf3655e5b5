#include "cli/stats.hpp"

#include <cstdio>

namespace ember::cli {

namespace {

std::string json_string(const std::string& s) {
  std::string out = "\"";
  for (const char c : s) {
    if (c == '"' || c == '\\') {
      out += '\\';
      out += c;
    } else if (static_cast<unsigned char>(c) < 0x20) {
      char buf[8];
      std::snprintf(buf, sizeof buf, "\\u%04x", static_cast<unsigned char>(c));
      out += buf;
    } else {
      out += c;
    }
  }
  return out + "\"";
}

}  // namespace

void print_stats(const BooleanResult& r, const char* operation, const std::vector<std::string>& inputs) {
  const BooleanStats& s = r.stats;
  std::size_t open_edges = 0, pairs = 0, misoriented = 0;
  bool pairs_complete = true;  // every operand's count is exact, not a lower bound
  std::string solid_check;
  for (std::size_t i = 0; i < s.operands.size(); ++i) {
    const OperandReport& o = s.operands[i];
    open_edges += o.open_edges;
    pairs += o.self_intersecting_pairs;
    pairs_complete &= !self_intersection_count_is_lower_bound(o);
    misoriented += o.misoriented_components;
    if (!solid_check.empty()) solid_check += "; ";
    solid_check += (i < inputs.size() ? inputs[i] : "operand " + std::to_string(i)) + ": " + describe_solid_check(o);
  }
  const auto count = [&](std::string_view name) { return static_cast<std::size_t>(s.diagnostic(name)); };
  const auto flag = [&](std::string_view name) { return s.diagnostic(name) != 0 ? 1 : 0; };
  std::fprintf(stderr,
               "{\"version\": \"%s\", \"operation\": %s, \"input_triangles\": %zu, \"dropped_degenerate\": %zu, "
               "\"collapsed_triangles\": %zu, \"flipped_triangles\": %zu, \"grid_step\": %.17g, "
               "\"output_polygons\": %zu, \"dropped_slivers\": %zu, \"solid_operands\": %zu, \"merged_triangles\": "
               "%zu, \"solid_path\": %d, \"direct_mesh\": %d, "
               "\"open_edges\": %zu, \"self_intersecting_pairs\": %zu, \"self_intersecting_pairs_complete\": %d, "
               "\"misoriented_components\": %zu, "
               "\"solid_check\": %s, \"output_vertices\": %zu, \"tjunctions_resolved\": %zu, "
               "\"collinear_removed\": %zu, \"regions\": %zu, \"fallback_regions\": %zu, "
               "\"rounded_degenerate\": %zu, \"time_ms\": %.3f, \"setup_ms\": %.3f, \"proof_ms\": %.3f, "
               "\"solve_ms\": %.3f, \"output_ms\": %.3f, \"weld_ms\": %.3f, \"tjunction_ms\": %.3f, "
               "\"regions_ms\": %.3f, \"triangulate_ms\": %.3f, \"threads\": %d}\n",
               EMBER_VERSION, json_string(operation).c_str(), s.input_triangles, s.dropped_degenerate,
               s.collapsed_triangles, s.flipped_triangles, s.grid_step, s.output_polygons, s.dropped_slivers,
               s.solid_operands, count("merged_triangles"), flag("solid_path"), flag("direct_mesh"), open_edges, pairs,
               pairs_complete ? 1 : 0, misoriented, json_string(solid_check).c_str(), s.output_vertices,
               count("tjunctions_resolved"), count("collinear_removed"), count("regions"), count("fallback_regions"),
               s.rounded_degenerate, s.time_ms, s.diagnostic("setup_ms"), s.diagnostic("proof_ms"),
               s.diagnostic("solve_ms"), s.diagnostic("output_ms"), s.diagnostic("weld_ms"),
               s.diagnostic("tjunction_ms"), s.diagnostic("regions_ms"), s.diagnostic("triangulate_ms"), s.threads);
}

}  // namespace ember::cli
