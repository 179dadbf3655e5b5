#pragma once
// Step 1 of the mesh stage (mesh_output.hpp): one id per exact point.
#include <array>
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "core/output/output_vertices.hpp"
#include "core/input/quantize.hpp"

namespace ember::core {

/// Step 1. Polygons keep their stored (unflipped) vertex order. With `ids`,
/// the corners of unbuilt triangles are welded through their input vertex
/// ids (faster; the same result).
OutputVertices exact_weld(std::span<const OutputPolygon> polys, const Quantizer& q, const InputTopology* ids = nullptr);

}  // namespace ember::core
