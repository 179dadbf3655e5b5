// Step 2b of the mesh stage: whole input triangles that need no region.
//
// Most of a typical result is input triangles that no cut touched (unbuilt
// output polygons). Step 3 would sort each by its plane, find it alone in
// its group or joined with nothing, give it a region with three boundary
// edges, and step 4 would emit the same three ids. A triangle skips all that
// when nothing can join it: step 3 joins two pieces only across an edge that
// both have (as an id pair, after step 2) and only when their oriented planes
// are equal. So a triangle passes through if step 2 gave it no vertex (its
// edges are its three corner pairs) and every other piece that has one of
// those pairs as an edge lies in a different oriented plane. Two pieces with
// a common edge share a point, so their planes are equal iff their normals
// are parallel, and equally oriented iff the normals point the same way.
#include "core/output/pass_through.hpp"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>

#include "core/output/output_vertices.hpp"
#include "core/output/tjunctions.hpp"
#include "core/support/sort_pairs.hpp"

namespace ember::core {

namespace {

std::uint64_t pair_key(std::uint64_t a, std::uint64_t b) { return (std::min(a, b) << 32) | std::max(a, b); }

/// The outward normal of a piece as a plane through the origin (only the
/// normal is read): its input triangle's grid normal, the same vector as its
/// support plane's, negated when the piece is emitted flipped. Cheaper than
/// support_of, which also forms the offset.
Plane oriented_normal(const OutputPolygon& p) {
  const std::array<IntPoint, 3>& c = *p.corners;
  const std::array<std::int64_t, 3> n = grid_normal(c[0], c[1], c[2]);
  const Plane plane{n[0], n[1], n[2], 0};
  return p.flip ? -plane : plane;
}

/// The edges that step 2 created (sub-edges of the polygons that gained a
/// vertex), by id pair: these pairs are not in EdgePairs.
std::vector<std::pair<std::uint64_t, std::uint32_t>> grown_edges(const OutputVertices& verts, const Cycles& cycles) {
  std::vector<std::pair<std::uint64_t, std::uint32_t>> out;
  for (std::uint32_t p = 0; p < cycles.size(); ++p) {
    const auto c = cycles[p];
    if (c.size() == verts.corners[p].size()) continue;
    for (std::size_t k = 0; k < c.size(); ++k) out.emplace_back(pair_key(c[k], c[(k + 1) % c.size()]), p);
  }
  sort_pairs(out);
  return out;
}

}  // namespace

std::vector<char> pass_through_triangles(std::span<const OutputPolygon> polys, const OutputVertices& verts,
                                         const EdgePairs& pairs, const Cycles& cycles) {
  const std::vector<std::pair<std::uint64_t, std::uint32_t>> grown = grown_edges(verts, cycles);
  std::vector<char> on_grown(verts.exact.size(), 0);  // end point of a step-2 edge: worth a lookup
  for (const auto& [key, piece] : grown) on_grown[key >> 32] = on_grown[key & 0xffffffffu] = 1;
  std::vector<char> through(polys.size(), 0);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, polys.size(), 512), [&](const auto& range) {
    for (std::size_t t = range.begin(); t != range.end(); ++t) {
      const OutputPolygon& tri = polys[t];
      if (tri.settled) {
        through[t] = 1;  // nothing can join it (OutputPolygon::settled)
        continue;
      }
      if (!unbuilt(tri) || cycles[t].size() != 3) continue;
      const Plane normal = oriented_normal(tri);
      const auto joins = [&](std::uint32_t q) {
        if (q == t) return false;
        const Plane other = oriented_normal(polys[q]);
        return parallel(normal, other) && same_orientation(normal, other);
      };
      bool alone = true;
      const auto ids = cycles[t];
      for (std::uint32_t k = 0; k < 3 && alone; ++k) {
        // The pieces that kept this corner edge whole (no vertex was inserted
        // into it: t gained none), then those whose step-2 sub-edges are it.
        const std::uint32_t run = pairs.run_of[verts.corners.offsets[t] + k];
        for (std::uint32_t i = pairs.run_begin[run]; i < pairs.run_begin[run + 1] && alone; ++i)
          alone = !joins(pairs.poly_of[pairs.corner[i]]);
        if (!on_grown[ids[k]] || !on_grown[ids[(k + 1) % 3]]) continue;
        const std::uint64_t key = pair_key(ids[k], ids[(k + 1) % 3]);
        for (auto it = std::lower_bound(grown.begin(), grown.end(), std::pair{key, 0u});
             it != grown.end() && it->first == key && alone; ++it)
          alone = !joins(it->second);
      }
      through[t] = alone;
    }
  });
  return through;
}

}  // namespace ember::core
