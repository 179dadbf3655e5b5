#pragma once
// Helpers of the solid proof's contact tests: grid triangles with welded ids
// and the all-pairs count that the broad phase must reproduce.
#include <algorithm>
#include <array>
#include <map>
#include <tuple>
#include <vector>

#include "core/solid_check.hpp"

namespace ember::test {

using Tri = std::array<IntPoint, 3>;

/// Contact triangles with ids equal iff positions equal (as the set-up's weld
/// gives). They refer to the corners in `tris`, which must outlive them.
inline std::vector<core::ContactTriangle> with_ids(const std::vector<Tri>& tris) {
  std::map<std::tuple<std::int64_t, std::int64_t, std::int64_t>, std::uint32_t> ids;
  std::vector<core::ContactTriangle> out;
  for (const Tri& t : tris) {
    std::array<std::uint32_t, 3> id{};
    for (int k = 0; k < 3; ++k)
      id[k] = ids.try_emplace({t[k].x, t[k].y, t[k].z}, static_cast<std::uint32_t>(ids.size())).first->second;
    out.push_back(core::contact_triangle(t, id));
  }
  return out;
}
std::vector<core::ContactTriangle> with_ids(std::vector<Tri>&&) = delete;  // would refer to a temporary

/// Per triangle and edge k (corner k to k + 1), the triangle across it when
/// the edge is manifold (used twice, in opposite directions), else
/// kNoNeighbor: what the set-up's edge matching gives (GridTriangles::neighbors).
inline std::vector<std::array<std::uint32_t, 3>> manifold_neighbours(const std::vector<core::ContactTriangle>& tris) {
  std::map<std::pair<std::uint32_t, std::uint32_t>, std::vector<std::pair<std::uint32_t, int>>> uses;  // undirected edge -> (triangle, edge)
  for (std::uint32_t t = 0; t < tris.size(); ++t)
    for (int k = 0; k < 3; ++k) {
      const std::uint32_t a = tris[t].id[k], b = tris[t].id[(k + 1) % 3];
      uses[{std::min(a, b), std::max(a, b)}].push_back({t, k});
    }
  std::vector<std::array<std::uint32_t, 3>> out(tris.size(), {core::kNoNeighbor, core::kNoNeighbor, core::kNoNeighbor});
  for (const auto& [edge, u] : uses) {
    if (u.size() != 2) continue;
    const auto from = [&](const std::pair<std::uint32_t, int>& x) { return tris[x.first].id[x.second]; };
    if (from(u[0]) == from(u[1])) continue;  // same direction twice
    out[u[0].first][u[0].second] = u[1].first;
    out[u[1].first][u[1].second] = u[0].first;
  }
  return out;
}

/// Pairs that meet improperly, by testing every pair.
inline std::size_t all_pairs_count(const std::vector<core::ContactTriangle>& tris) {
  std::size_t n = 0;
  for (std::size_t i = 0; i < tris.size(); ++i)
    for (std::size_t j = i + 1; j < tris.size(); ++j) n += core::triangles_meet_improperly(tris[i], tris[j]);
  return n;
}

}  // namespace ember::test
