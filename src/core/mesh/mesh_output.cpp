// The mesh stage's driver: exact weld, T-junction insertion, region merge,
// collinear-vertex removal, triangulation, then one indexed triangle mesh.
#include "core/mesh/mesh_output.hpp"

#include <tbb/parallel_for.h>

#include <algorithm>

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

struct RegionTriangles {
  std::vector<std::array<std::uint32_t, 3>> tris;
  std::vector<std::uint32_t> source;  ///< per triangle (fallback pieces keep their own)
  bool fallback = false;
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
  const OutputVertices verts = exact_weld(polys, q);
  const Cycles cycles = insert_tjunction_vertices(polys, verts, out.stats.tjunctions);
  Regions regions = build_regions(polys, cycles, verts);
  const std::vector<Removal> removals = remove_collinear_vertices(regions, verts.exact.size());
  out.stats.regions = regions.regions.size();

  const std::size_t n_regions = regions.regions.size();
  std::vector<RegionTriangles> per_region(n_regions);
  std::vector<char> failed(n_regions, 0), undone(removals.size(), 0);
  auto triangulate = [&](std::span<const std::uint32_t> which) {
    tbb::parallel_for(std::size_t{0}, which.size(), [&](std::size_t i) {
      const std::uint32_t r = which[i];
      RegionTriangles& rt = per_region[r];
      rt.tris.clear();
      if (triangulate_region(regions, r, verts, rt.tris))
        rt.source.assign(rt.tris.size(), regions.regions[r].source);
      else
        failed[r] = 1;
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
  tbb::parallel_for(std::size_t{0}, n_regions, [&](std::size_t r) {
    if (!failed[r]) return;
    // Fallback: each convex piece on its own (always possible: a convex
    // polygon with points on its sides has a strictly convex ear).
    RegionTriangles& rt = per_region[r];
    const Region& region = regions.regions[r];
    rt.fallback = true;
    rt.tris.clear();
    rt.source.clear();
    for (const std::uint32_t p : region.pieces) {
      std::vector<std::uint32_t> loop = piece_loop(polys[p], cycles[p]);
      if (loop.size() >= 3) triangulate_loop(std::move(loop), region.plane, verts, rt.tris);
      rt.source.resize(rt.tris.size(), polys[p].id);
    }
  });

  // Vertices in order of first use, so numbering follows the output order.
  std::vector<std::uint32_t> remap(verts.exact.size(), UINT32_MAX);
  Mesh& mesh = out.mesh;
  for (std::size_t r = 0; r < per_region.size(); ++r) {
    const RegionTriangles& rt = per_region[r];
    out.stats.fallback_regions += rt.fallback;
    for (std::size_t i = 0; i < rt.tris.size(); ++i) {
      std::array<std::uint32_t, 3> t{};
      for (int c = 0; c < 3; ++c) {
        std::uint32_t& id = remap[rt.tris[i][c]];
        if (id == UINT32_MAX) id = mesh.add_vertex(verts.rounded[rt.tris[i][c]]);
        t[c] = id;
      }
      if (rounded_area_is_zero(mesh.vertices, t)) ++out.stats.rounded_degenerate;
      mesh.add_face({t[0], t[1], t[2]});
      out.provenance.push_back(sources[rt.source[i]]);
    }
  }
  return out;
}

}  // namespace ember::core
