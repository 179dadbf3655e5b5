// Stage 4 of the Boolean (build_output.hpp).
#include "core/output/build_output.hpp"

#include "core/output/polygon_export.hpp"

namespace ember::core {

BuiltOutput build_output(RouteResult&& route, PreparedInput& input, BooleanOptions::Output form,
                         std::span<const std::uint32_t> source_groups) {
  BuiltOutput out;
  const InputTriangles& in = input.triangles;
  if (form == BooleanOptions::Output::Polygons) {
    out.mesh = export_polygons(route.polys, input.quantizer, in.sources, out.provenance, out.dropped_slivers);
    return out;
  }
  MeshOutput m;
  if (route.mesh) {
    m = std::move(*route.mesh);
  } else {
    InputTopology* topology = input.topology ? &*input.topology : nullptr;
    if (topology) {
      topology->by_triangle = in.grid.vertex_ids;
      topology->manifold_edges = in.grid.manifold_edges;
    }
    m = build_triangle_mesh(route.polys, input.quantizer, in.sources, topology, source_groups);
  }
  out.mesh = std::move(m.mesh);
  out.provenance = std::move(m.provenance);
  out.stats = m.stats;
  return out;
}

}  // namespace ember::core
