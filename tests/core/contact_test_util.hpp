#pragma once
// Helpers of the solid proof's contact tests: grid triangles with welded ids
// and the all-pairs count that the broad phase must reproduce.
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

/// Pairs that meet improperly, by testing every pair.
inline std::size_t all_pairs_count(const std::vector<core::ContactTriangle>& tris) {
  std::size_t n = 0;
  for (std::size_t i = 0; i < tris.size(); ++i)
    for (std::size_t j = i + 1; j < tris.size(); ++j) n += core::triangles_meet_improperly(tris[i], tris[j]);
  return n;
}

}  // namespace ember::test
