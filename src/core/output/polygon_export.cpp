// The polygon export (polygon_export.hpp).
#include "core/output/polygon_export.hpp"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <cstdint>
#include <cstring>
#include <unordered_map>

#include "core/output/mesh_output.hpp"

namespace ember::core {

Mesh export_polygons(const std::vector<OutputPolygon>& polys, const Quantizer& q, std::span<const Provenance> sources,
                     std::vector<Provenance>& provenance, std::size_t& dropped) {
  struct Key {
    std::uint64_t v[3];
    bool operator==(const Key& o) const { return std::memcmp(v, o.v, sizeof v) == 0; }
  };
  struct KeyHash {
    std::size_t operator()(const Key& k) const { return (k.v[0] * 0x9e3779b97f4a7c15ULL) ^ (k.v[1] * 31) ^ k.v[2]; }
  };
  // Round every vertex in parallel (the costly part), then weld serially in
  // output order so vertex numbering is deterministic.
  std::vector<std::size_t> offset(polys.size() + 1, 0);
  for (std::size_t i = 0; i < polys.size(); ++i) offset[i + 1] = offset[i] + corner_count(polys[i]);
  std::vector<Vec3d> rounded(offset.back());
  tbb::parallel_for(
      tbb::blocked_range<std::size_t>(0, polys.size(), 256), [&](const tbb::blocked_range<std::size_t>& r) {
        for (std::size_t i = r.begin(); i != r.end(); ++i) {
          const OutputPolygon& p = polys[i];
          const std::size_t n = corner_count(p);
          for (std::size_t k = 0; k < n; ++k) {
            const std::size_t at = p.flip ? n - 1 - k : k;
            const Vec3d x = unbuilt(p) ? q.dequantize((*p.corners)[at]) : q.dequantize(p.vertices[at]);
            rounded[offset[i] + k] = {x.x + 0.0, x.y + 0.0, x.z + 0.0};  // -0.0 -> +0.0 so equal points weld
          }
        }
      });
  Mesh mesh;
  std::unordered_map<Key, std::uint32_t, KeyHash> ids;
  ids.reserve(rounded.size() / 2);
  std::vector<std::uint32_t> face;
  for (std::size_t i = 0; i < polys.size(); ++i) {
    const OutputPolygon& p = polys[i];
    face.clear();
    for (std::size_t k = offset[i]; k < offset[i + 1]; ++k) {
      const Vec3d& x = rounded[k];
      Key key{};
      std::memcpy(&key.v[0], &x.x, 8);
      std::memcpy(&key.v[1], &x.y, 8);
      std::memcpy(&key.v[2], &x.z, 8);
      auto [it, fresh] = ids.try_emplace(key, static_cast<std::uint32_t>(mesh.vertices.size()));
      if (fresh) mesh.vertices.push_back(x);
      // Distinct exact points may round to the same double: drop repeats.
      if (face.empty() || face.back() != it->second) face.push_back(it->second);
    }
    while (face.size() > 1 && face.front() == face.back()) face.pop_back();
    // An exact sliver can round to collinear doubles; such a face has no area
    // in the caller's units and is dropped rather than emitted degenerate.
    if (face.size() < 3 || rounded_area_is_zero(mesh.vertices, face)) {
      ++dropped;
      continue;
    }
    mesh.add_face(face);
    provenance.push_back(sources[p.id]);
  }
  return mesh;
}

}  // namespace ember::core
