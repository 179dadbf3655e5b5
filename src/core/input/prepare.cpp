// Stage 1 of the Boolean (prepare.hpp).
#include "core/input/prepare.hpp"

#include <tbb/parallel_invoke.h>

#include "core/input/grid_input.hpp"
#include "ember/error.hpp"

namespace ember::core {

std::string operand_name(std::size_t i) { return "operand " + std::to_string(i); }

namespace {

/// The welded ids of all operands numbered in one range: operand o's ids
/// start at operand_base[o]. None when they do not fit 32 bits.
std::optional<InputTopology> number_vertices(const std::vector<std::size_t>& vertex_count) {
  InputTopology topology;
  topology.operand_base.push_back(0);
  for (const std::size_t count : vertex_count) {
    if (count > UINT32_MAX - 1 - topology.operand_base.back()) return std::nullopt;
    topology.operand_base.push_back(topology.operand_base.back() + static_cast<std::uint32_t>(count));
  }
  return topology;
}

/// Records the open edges per operand; an open operand is an error unless
/// allowed, and then a warning.
void check_closed(const std::vector<std::size_t>& open, bool allow_open, PreparedInput& out) {
  for (std::size_t o = 0; o < open.size(); ++o) {
    out.reports[o].open_edges = open[o];
    if (open[o] == 0) continue;
    out.reports[o].solid = SolidStatus::Open;
    const std::string msg = "not closed: " + std::to_string(open[o]) +
                            " edges are not matched by an opposite edge, so inside/outside is undefined";
    if (!allow_open) throw Error(msg + "; repair the mesh or allow open inputs (CLI: --allow-open)", {.operand = o});
    out.warnings.push_back(operand_name(o) + ": " + msg + "; proceeding as requested, the result may have holes");
  }
}

}  // namespace

PreparedInput prepare_input(std::span<const Mesh> operands, bool allow_open) {
  PreparedInput out;
  validate_operands(operands);
  const UsedVertices used = used_vertices(operands);
  out.quantizer = fit_used_vertices(operands, used);
  GridInput gi = to_grid(operands, out.quantizer, used);
  out.reports.resize(operands.size());
  // Independent: side by side for small inputs (side_by_side; an exception
  // from the audit reaches the caller either way).
  EdgeMatching edges;
  const auto audit = [&] { audit_quantization(operands, gi, out.quantizer, out.reports, out.warnings); };
  const auto match = [&] { edges = match_edges(gi); };
  if (side_by_side(gi)) {
    tbb::parallel_invoke(audit, match);
  } else {
    audit();
    match();
  }
  out.triangles = build_grid_triangles(gi, edges);
  out.input_triangles = gi.triangles.size();
  out.lo = gi.lo;
  out.hi = gi.hi;
  out.topology = number_vertices(gi.vertex_count);
  out.open_edges = std::move(edges.open);
  check_closed(out.open_edges, allow_open, out);
  return out;
}

}  // namespace ember::core
