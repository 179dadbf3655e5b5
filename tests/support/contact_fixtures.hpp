#pragma once
// Helpers of the solid proof's contact tests: grid triangles with welded ids
// and the all-pairs count that the broad phase must reproduce.
#include <algorithm>
#include <array>
#include <map>
#include <random>
#include <tuple>
#include <vector>

#include "core/model/grid_triangles.hpp"
#include "core/search/contact_triangle.hpp"
#include "core/search/triangle_contact.hpp"

namespace ember::test {

using Tri = std::array<IntPoint, 3>;

inline bool degenerate(const Tri& t) {
  const std::array<std::int64_t, 3> n = grid_normal(t[0], t[1], t[2]);
  return n[0] == 0 && n[1] == 0 && n[2] == 0;
}

/// The grid normals of a GridTriangles filled by hand (the set-up stores
/// them as it builds the triangles).
inline void set_normals(core::GridTriangles& grid) {
  grid.normals.resize(grid.corners.size());
  for (std::size_t i = 0; i < grid.corners.size(); ++i)
    grid.normals[i] = grid_normal(grid.corners[i][0], grid.corners[i][1], grid.corners[i][2]);
}

/// A rod of `count` long slivers along the diagonal-free direction d =
/// (-47, 88, 9) (the sliver pile's rods run near it), placed at random in
/// its section around `centre`, about 20,000 units long and tens to
/// thousands wide: their boxes overlap by the dozens, and some of them
/// cross.
inline std::vector<Tri> sliver_rod(std::size_t count, const IntPoint& centre, unsigned seed) {
  const IntPoint d{-47, 88, 9}, u{88, 47, 0}, v{-423, 792, -9953};  // u, v orthogonal to d
  std::mt19937 rng(seed);
  std::uniform_int_distribution<std::int64_t> along(0, 100), across(-20, 20), jitter(-60, 60), wide(-400, 400);
  const auto at = [&](std::int64_t s, std::int64_t a, std::int64_t b) {
    return IntPoint{centre.x + s * d.x + a * u.x + b * v.x / 10, centre.y + s * d.y + a * u.y + b * v.y / 10,
                    centre.z + s * d.z + a * u.z + b * v.z / 10};
  };
  std::vector<Tri> tris;
  while (tris.size() < count) {
    const IntPoint c = at(along(rng), across(rng), across(rng));
    const IntPoint e = at(200, 0, 0);  // 200 d from the centre
    Tri t{c,
          {c.x + e.x - centre.x + jitter(rng), c.y + e.y - centre.y + jitter(rng), c.z + e.z - centre.z + jitter(rng)},
          {c.x + wide(rng), c.y + wide(rng), c.z + wide(rng)}};
    if (tris.size() % 7 == 3) t[2] = at(along(rng) + 50, across(rng), across(rng));  // a wide one across the section
    if (!degenerate(t)) tris.push_back(t);
  }
  return tris;
}

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
  std::map<std::pair<std::uint32_t, std::uint32_t>, std::vector<std::pair<std::uint32_t, int>>>
      uses;  // undirected edge -> (triangle, edge)
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
