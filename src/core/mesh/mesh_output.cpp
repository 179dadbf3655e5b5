// The mesh stage's driver: exact weld, T-junction insertion, region merge,
// collinear-vertex removal, triangulation, then one indexed triangle mesh.
#include "core/mesh/mesh_output.hpp"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <chrono>

namespace ember::core {

namespace {

/// A piece's cycle around its outward normal, repeated ids dropped.
std::vector<std::uint32_t> piece_loop(const OutputPolygon& poly, std::span<const std::uint32_t> ids) {
  std::vector<std::uint32_t> loop;
  for (const std::uint32_t v : ids)
    if (loop.empty() || loop.back() != v) loop.push_back(v);
  while (loop.size() > 1 && loop.front() == loop.back()) loop.pop_back();
  if (poly.flip) std::reverse(loop.begin(), loop.end());
  return loop;
}

double ms_since(std::chrono::steady_clock::time_point& t) {
  const auto now = std::chrono::steady_clock::now();
  const double ms = std::chrono::duration<double, std::milli>(now - t).count();
  t = now;
  return ms;
}

/// Triangles of a region triangulated piece by piece, each with its piece's source.
struct RegionTriangles {
  std::vector<std::array<std::uint32_t, 3>> tris;
  std::vector<std::uint32_t> source;
};

}  // namespace

bool rounded_area_is_zero(const std::vector<Vec3d>& pos, std::span<const std::uint32_t> face) {
  using ld = long double;
  const Vec3d& o = pos[face[0]];
  ld n[3] = {0, 0, 0};
  for (std::size_t k = 1; k + 1 < face.size(); ++k) {
    const Vec3d &a = pos[face[k]], &b = pos[face[k + 1]];
    const ld ax = ld(a.x) - o.x, ay = ld(a.y) - o.y, az = ld(a.z) - o.z;
    const ld bx = ld(b.x) - o.x, by = ld(b.y) - o.y, bz = ld(b.z) - o.z;
    n[0] += ay * bz - az * by;
    n[1] += az * bx - ax * bz;
    n[2] += ax * by - ay * bx;
  }
  return n[0] == 0 && n[1] == 0 && n[2] == 0;
}

MeshOutput build_triangle_mesh(std::span<const OutputPolygon> polys, const Quantizer& q,
                               std::span<const Provenance> sources) {
  MeshOutput out;
  auto clock = std::chrono::steady_clock::now();
  const OutputVertices verts = exact_weld(polys, q);
  out.stats.weld_ms = ms_since(clock);
  const Cycles cycles = insert_tjunction_vertices(polys, verts, out.stats.tjunctions);
  out.stats.tjunction_ms = ms_since(clock);
  Regions regions = build_regions(polys, cycles, verts);
  const std::vector<Removal> removals = remove_collinear_vertices(regions, verts.exact.size());
  out.stats.regions_ms = ms_since(clock);
  out.stats.regions = regions.regions.size();

  // Each region's triangles go to a slot of the flat list; a polygon with h
  // holes and V boundary vertices has at most V + 2h - 2 triangles, and a hole
  // has at least 3 vertices, so V + 2 (V / 3) slots always suffice.
  const std::size_t n_regions = regions.regions.size();
  std::vector<std::size_t> slot(n_regions + 1, 0);
  for (std::size_t r = 0; r < n_regions; ++r) {
    std::size_t v = 0;
    for (std::uint32_t e = regions.edge_begin[r]; e < regions.edge_begin[r + 1]; ++e) v += regions.edges[e].alive;
    slot[r + 1] = slot[r] + v + 2 * (v / 3);
  }
  std::vector<std::array<std::uint32_t, 3>> slots(slot.back());
  std::vector<std::uint32_t> count(n_regions, 0);
  std::vector<char> failed(n_regions, 0), undone(removals.size(), 0);
  auto triangulate = [&](std::span<const std::uint32_t> which) {
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, which.size(), 64), [&](const auto& range) {
      std::vector<std::array<std::uint32_t, 3>> tris;
      for (std::size_t i = range.begin(); i != range.end(); ++i) {
        const std::uint32_t r = which[i];
        tris.clear();
        if (!triangulate_region(regions, r, verts, tris) || tris.size() > slot[r + 1] - slot[r]) {
          failed[r] = 1;
          continue;
        }
        std::copy(tris.begin(), tris.end(), slots.begin() + static_cast<std::ptrdiff_t>(slot[r]));
        count[r] = static_cast<std::uint32_t>(tris.size());
      }
    });
  };
  std::vector<std::uint32_t> all(n_regions);
  for (std::uint32_t r = 0; r < n_regions; ++r) all[r] = r;
  triangulate(all);
  // A failed region is triangulated piece by piece below, and its pieces keep
  // every vertex: put the removed ones back on both sides and redo the
  // neighbours that changed (which may fail in turn).
  for (;;) {
    std::vector<std::uint32_t> changed = restore_vertices(regions, removals, failed, undone);
    if (changed.empty()) break;
    triangulate(changed);
  }
  for (const char u : undone) out.stats.collinear_removed += !u;
  std::vector<std::uint32_t> failed_regions;
  for (std::uint32_t r = 0; r < n_regions; ++r)
    if (failed[r]) failed_regions.push_back(r);
  out.stats.fallback_regions = failed_regions.size();
  std::vector<RegionTriangles> fallback(failed_regions.size());
  tbb::parallel_for(std::size_t{0}, failed_regions.size(), [&](std::size_t i) {
    // Fallback: each convex piece on its own (always possible: a convex
    // polygon with points on its sides has a strictly convex ear).
    RegionTriangles& rt = fallback[i];
    const Region& region = regions.regions[failed_regions[i]];
    for (const std::uint32_t p : region.pieces) {
      std::vector<std::uint32_t> loop = piece_loop(polys[p], cycles[p]);
      if (loop.size() >= 3) triangulate_loop(std::move(loop), region.plane, verts, rt.tris);
      rt.source.resize(rt.tris.size(), polys[p].id);
    }
  });

  // Vertices in order of first use, so numbering follows the output order.
  std::vector<std::uint32_t> remap(verts.exact.size(), UINT32_MAX);
  Mesh& mesh = out.mesh;
  std::size_t next_fallback = 0;
  auto emit = [&](const std::array<std::uint32_t, 3>& tri, std::uint32_t source) {
    std::array<std::uint32_t, 3> t{};
    for (int c = 0; c < 3; ++c) {
      std::uint32_t& id = remap[tri[c]];
      if (id == UINT32_MAX) id = mesh.add_vertex(verts.rounded[tri[c]]);
      t[c] = id;
    }
    if (rounded_area_is_zero(mesh.vertices, t)) ++out.stats.rounded_degenerate;
    mesh.add_face({t[0], t[1], t[2]});
    out.provenance.push_back(sources[source]);
  };
  for (std::size_t r = 0; r < n_regions; ++r) {
    if (failed[r]) {
      const RegionTriangles& rt = fallback[next_fallback++];
      for (std::size_t i = 0; i < rt.tris.size(); ++i) emit(rt.tris[i], rt.source[i]);
      continue;
    }
    for (std::size_t i = slot[r]; i < slot[r] + count[r]; ++i) emit(slots[i], regions.regions[r].source);
  }
  out.stats.triangulate_ms = ms_since(clock);
  return out;
}

}  // namespace ember::core
