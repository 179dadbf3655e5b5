#include "core/weld.hpp"

#include <unordered_map>

namespace ember::core {

namespace {
struct PointHash {
  std::size_t operator()(const IntPoint& p) const {
    std::uint64_t h = static_cast<std::uint64_t>(p.x) * 0x9e3779b97f4a7c15ULL;
    h ^= static_cast<std::uint64_t>(p.y) + 0x7f4a7c159e3779b9ULL + (h << 6) + (h >> 2);
    h ^= static_cast<std::uint64_t>(p.z) + 0x94d049bb133111ebULL + (h << 6) + (h >> 2);
    return h;
  }
};
}  // namespace

WeldedTriangles weld(std::span<const std::array<IntPoint, 3>> triangles) {
  std::unordered_map<IntPoint, std::uint32_t, PointHash> ids;
  ids.reserve(triangles.size());
  WeldedTriangles out;
  out.ids.resize(triangles.size());
  for (std::size_t t = 0; t < triangles.size(); ++t)
    for (int e = 0; e < 3; ++e)
      out.ids[t][e] = ids.try_emplace(triangles[t][e], static_cast<std::uint32_t>(ids.size())).first->second;
  out.vertex_count = ids.size();
  return out;
}

}  // namespace ember::core
