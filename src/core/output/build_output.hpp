#pragma once
// Stage 4 of the Boolean (boolean.cpp): the route's result in the caller's
// units, as a watertight triangle mesh (the mesh stage, mesh_output.hpp) or
// as the core's raw polygons (polygon_export.hpp).
#include <cstddef>
#include <vector>

#include "core/input/prepare.hpp"
#include "core/output/mesh_output.hpp"
#include "core/route/route.hpp"
#include "ember/boolean.hpp"

namespace ember::core {

struct BuiltOutput {
  Mesh mesh;
  std::vector<Provenance> provenance;  ///< one per face of mesh
  MeshOutputStats stats;               ///< the mesh stage's counts and times (triangle output)
  std::size_t dropped_slivers = 0;     ///< polygon output: faces with no area once rounded
};

/// Run it inside the Boolean's task arena. `input`'s topology must carry
/// the proof's solid flags.
/// `source_groups` (optional): the face group of each source id (triangle
/// output keeps coplanar faces of different groups apart).
BuiltOutput build_output(RouteResult&& route, PreparedInput& input, BooleanOptions::Output form,
                         std::span<const std::uint32_t> source_groups = {});

}  // namespace ember::core
