#pragma once
// The core's raw convex pieces as a polygon mesh (BooleanOptions::Output::Polygons).
#include <cstddef>
#include <span>
#include <vector>

#include "core/input/quantize.hpp"
#include "core/model/output_polygon.hpp"
#include "ember/mesh.hpp"

namespace ember::core {

/// One face per output polygon (flipped ones reversed), vertices rounded to
/// double and welded by their rounded position in output order (so the
/// numbering does not depend on scheduling). A face whose rounded corners
/// have no area is dropped and counted in `dropped`; `provenance` gets
/// sources[id] of every face kept.
Mesh export_polygons(const std::vector<OutputPolygon>& polys, const Quantizer& q, std::span<const Provenance> sources,
                     std::vector<Provenance>& provenance, std::size_t& dropped);

}  // namespace ember::core
