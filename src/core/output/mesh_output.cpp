// The mesh stage's driver: exact weld, T-junction insertion, region merge,
// collinear-vertex removal, triangulation, then one indexed triangle mesh.
#include "core/output/mesh_output.hpp"
#include "core/output/output_vertices.hpp"
#include "core/output/exact_weld.hpp"
#include "core/output/tjunctions.hpp"
#include "core/output/pass_through.hpp"
#include "core/output/regions.hpp"
#include "core/output/collinear.hpp"
#include "core/output/region_triangulation.hpp"
#include "core/output/diagonals.hpp"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_invoke.h>
#include <tbb/parallel_scan.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <functional>
#include <numeric>
#include <optional>

#include "core/support/fill_vector.hpp"
#include "core/output/vertex_index.hpp"
#include "core/support/parallel_select.hpp"

namespace ember::core {

namespace {

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

void write_indexed_mesh(std::span<const std::array<std::uint32_t, 3>> tris, std::size_t vertex_count,
                        const std::function<Vec3d(std::uint32_t)>& position, std::size_t whole_count, Mesh& mesh,
                        std::size_t& rounded_degenerate) {
  const std::size_t total = tris.size();
  // A vertex's number is the rank of its first use among all first uses
  // (3 * triangle + corner): flag the corners that are one, then a prefix
  // count along the corners, all in parallel, as a serial pass would number them.
  FillVector<std::uint64_t> first_use = parallel_filled<std::uint64_t>(vertex_count, UINT64_MAX);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, total, 1024), [&](const auto& range) {
    for (std::size_t t = range.begin(); t != range.end(); ++t)
      for (int c = 0; c < 3; ++c) atomic_min(first_use[tris[t][c]], 3 * t + static_cast<std::uint64_t>(c));
  });
  const std::size_t corners = 3 * total;
  FillVector<std::uint32_t> rank(corners + 1);  // flag, then the exclusive prefix count; every entry written
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, total, 1024), [&](const auto& range) {
    for (std::size_t t = range.begin(); t != range.end(); ++t)
      for (std::size_t k = 0; k < 3; ++k) rank[3 * t + k] = first_use[tris[t][k]] == 3 * t + k;
  });
  rank[corners] = 0;
  const std::uint32_t vertices = tbb::parallel_scan(
      tbb::blocked_range<std::size_t>(0, corners + 1, 4096), std::uint32_t{0},
      [&](const tbb::blocked_range<std::size_t>& range, std::uint32_t sum, bool final) {
        for (std::size_t c = range.begin(); c != range.end(); ++c) {
          const std::uint32_t flag = rank[c];
          if (final) rank[c] = sum;
          sum += flag;
        }
        return sum;
      },
      [](std::uint32_t a, std::uint32_t b) { return a + b; });
  const auto remap = [&](std::uint32_t v) { return rank[first_use[v]]; };
  // The mesh's arrays are plain vectors: their resize value-initializes
  // serially, so their pages are faulted in first, in parallel (on a large
  // output the three are tens of megabytes).
  reserve_touched(mesh.vertices, vertices);
  reserve_touched(mesh.indices, 3 * total);
  reserve_touched(mesh.face_offsets, total + 1);
  mesh.vertices.resize(vertices);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, first_use.size(), 4096), [&](const auto& range) {
    for (std::size_t v = range.begin(); v != range.end(); ++v)
      if (first_use[v] != UINT64_MAX) mesh.vertices[rank[first_use[v]]] = position(static_cast<std::uint32_t>(v));
  });
  mesh.indices.resize(3 * total);
  mesh.face_offsets.resize(total + 1);
  std::atomic<std::size_t> degenerate{0};
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, total, 1024), [&](const auto& range) {
    std::size_t local = 0;
    for (std::size_t t = range.begin(); t != range.end(); ++t) {
      for (int c = 0; c < 3; ++c) mesh.indices[3 * t + static_cast<std::size_t>(c)] = remap(tris[t][c]);
      mesh.face_offsets[t + 1] = static_cast<std::uint32_t>(3 * (t + 1));
      // A whole input triangle has area; rounded exactly, its area vector
      // is its grid normal times 2^-2k, which the extended sum below forms
      // exactly (grid differences <= 2^26, products <= 2^52).
      static_assert(kCoordLimit <= (std::int64_t{1} << 25) && 2 * 26 < 64,
                    "whole-triangle area: grid differences <= 2^26, products <= 2^52, exact in long double");
      if (t < whole_count) continue;
      local += rounded_area_is_zero(mesh.vertices, std::span<const std::uint32_t>(mesh.indices.data() + 3 * t, 3));
    }
    degenerate += local;
  });
  mesh.face_offsets[0] = 0;
  rounded_degenerate = degenerate;
}

namespace {

/// The pass-through triangles in polygon order (most of a lightly touched
/// result), written in parallel at offsets counted per block; their corners
/// are pinned (no collinear removal: the regions do not see their edges).
void collect_direct(std::span<const OutputPolygon> polys, const Cycles& cycles, const std::vector<char>& through,
                    RegionTriangles& direct, std::vector<char>& pinned) {
  constexpr std::size_t kBlock = 4096;
  const std::size_t n = polys.size(), blocks = (n + kBlock - 1) / kBlock;
  std::vector<std::size_t> at(blocks + 1, 0);
  tbb::parallel_for(std::size_t{0}, blocks, [&](std::size_t b) {
    for (std::size_t p = b * kBlock; p < std::min(n, (b + 1) * kBlock); ++p) at[b + 1] += through[p] != 0;
  });
  std::partial_sum(at.begin(), at.end(), at.begin());
  direct.tris.resize(at.back());
  direct.source.resize(at.back());
  tbb::parallel_for(std::size_t{0}, blocks, [&](std::size_t b) {
    std::size_t slot = at[b];
    for (std::size_t p = b * kBlock; p < std::min(n, (b + 1) * kBlock); ++p) {
      if (!through[p]) continue;
      const auto c = cycles[p];
      direct.tris[slot] = polys[p].flip ? std::array{c[0], c[2], c[1]} : std::array{c[0], c[1], c[2]};
      direct.source[slot++] = polys[p].id;
      for (const std::uint32_t v : c) std::atomic_ref<char>(pinned[v]).store(1, std::memory_order_relaxed);
    }
  });
}

/// The triangles in output order: the pass-through triangles (`direct`, in
/// polygon order), then the regions' triangles in region order (a region in
/// `override_regions` takes its triangles from `overrides` instead of its
/// slot: piece-by-piece fallbacks and regions whose diagonals were split),
/// each with its provenance.
void assemble(const RegionTriangles& direct, const Regions& regions,
              const std::vector<std::array<std::uint32_t, 3>>& slots, const std::vector<std::size_t>& slot,
              const std::vector<std::uint32_t>& count, const std::vector<std::uint32_t>& override_regions,
              const std::vector<RegionTriangles>& overrides, std::span<const Provenance> sources,
              FillVector<std::array<std::uint32_t, 3>>& tris, std::vector<Provenance>& provenance) {
  const std::size_t n_regions = regions.regions.size();
  std::vector<std::uint32_t> override_of(n_regions, UINT32_MAX);
  for (std::uint32_t i = 0; i < override_regions.size(); ++i) override_of[override_regions[i]] = i;
  std::vector<std::size_t> first(n_regions + 1, direct.tris.size());
  for (std::size_t r = 0; r < n_regions; ++r)
    first[r + 1] = first[r] + (override_of[r] != UINT32_MAX ? overrides[override_of[r]].tris.size() : count[r]);
  const std::size_t total = first[n_regions];
  tris.resize(total);  // every triangle written below
  provenance.resize(total);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, direct.tris.size(), 1024), [&](const auto& range) {
    for (std::size_t t = range.begin(); t != range.end(); ++t) {
      tris[t] = direct.tris[t];
      provenance[t] = sources[direct.source[t]];
    }
  });
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n_regions, 256), [&](const auto& range) {
    for (std::size_t r = range.begin(); r != range.end(); ++r) {
      for (std::size_t i = 0; i < first[r + 1] - first[r]; ++i) {
        const std::size_t t = first[r] + i;
        if (override_of[r] != UINT32_MAX) {
          tris[t] = overrides[override_of[r]].tris[i];
          provenance[t] = sources[overrides[override_of[r]].source[i]];
        } else {
          tris[t] = slots[slot[r] + i];
          provenance[t] = sources[regions.regions[r].source];
        }
      }
    }
  });
}

}  // namespace

MeshOutput build_triangle_mesh(std::span<const OutputPolygon> polys, const Quantizer& q,
                               std::span<const Provenance> sources, const InputTopology* ids,
                               std::span<const std::uint32_t> source_groups) {
  MeshOutput out;
  auto clock = std::chrono::steady_clock::now();
  const OutputVertices verts = exact_weld(polys, q, ids);
  out.stats.weld_ms = ms_since(clock);
  // Independent, and each mostly one sort and one serial pass: side by side.
  std::optional<VertexIndex> index_slot;
  EdgePairs pairs;
  tbb::parallel_invoke([&] { index_slot.emplace(index_output_vertices(polys, verts, ids)); },
                       [&] { pairs = group_edges_by_pair(verts.corners, polys); });
  const VertexIndex& index = *index_slot;
  const Cycles cycles = insert_tjunction_vertices(polys, verts, index, pairs, out.stats.tjunctions, ids);
  out.stats.tjunction_ms = ms_since(clock);
  // Whole triangles that nothing can join go straight to the output; their
  // corners stay where they are.
  const std::vector<char> through = pass_through_triangles(polys, verts, pairs, cycles);
  RegionTriangles direct;
  std::vector<char> pinned(verts.exact.size(), 0);
  collect_direct(polys, cycles, through, direct, pinned);
  Regions regions = build_regions(polys, cycles, verts, through, source_groups);
  const std::vector<Removal> removals = remove_collinear_vertices(regions, verts.exact.size(), pinned);
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
    for (const std::uint32_t p : regions.pieces(failed_regions[i])) {
      std::vector<std::uint32_t> loop;
      piece_loop(polys[p], cycles[p], loop);
      if (loop.size() >= 3) triangulate_loop(loop, region.plane, verts, rt.tris);
      rt.source.resize(rt.tris.size(), polys[p].id);
    }
  });

  // Step 5b: a diagonal may pass through a point where another part of the
  // result touches the region; such regions get their split triangles.
  std::vector<char> used = std::move(pinned);  // atomic stores: several regions share vertices
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n_regions, 256), [&](const auto& range) {
    for (std::size_t r = range.begin(); r != range.end(); ++r)
      if (!failed[r])
        for (std::size_t i = slot[r]; i < slot[r] + count[r]; ++i)
          for (const std::uint32_t v : slots[i]) std::atomic_ref<char>(used[v]).store(1, std::memory_order_relaxed);
  });
  for (const RegionTriangles& rt : fallback)
    for (const auto& t : rt.tris)
      for (const std::uint32_t v : t) used[v] = 1;
  std::vector<std::vector<std::array<std::uint32_t, 3>>> split(n_regions);
  std::atomic<std::size_t> diagonal_points{0};
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n_regions, 64), [&](const auto& range) {
    std::vector<std::array<std::uint32_t, 3>> tris;
    for (std::size_t r = range.begin(); r != range.end(); ++r) {
      if (failed[r] || count[r] < 2) continue;
      tris.assign(slots.begin() + static_cast<std::ptrdiff_t>(slot[r]),
                  slots.begin() + static_cast<std::ptrdiff_t>(slot[r] + count[r]));
      if (const std::size_t k = split_diagonals(regions.regions[r].plane, verts, index, used, tris)) {
        split[r] = tris;
        diagonal_points += k;
      }
    }
  });
  out.stats.tjunctions += diagonal_points;
  // Regions whose triangles are not in their slot: fallbacks and split ones, in region order.
  std::vector<std::uint32_t> override_regions;
  std::vector<RegionTriangles> overrides;
  for (std::uint32_t r = 0, f = 0; r < n_regions; ++r) {
    if (failed[r]) {
      override_regions.push_back(r);
      overrides.push_back(std::move(fallback[f++]));
    } else if (!split[r].empty()) {
      override_regions.push_back(r);
      overrides.push_back({std::move(split[r]), {}});
      overrides.back().source.assign(overrides.back().tris.size(), regions.regions[r].source);
    }
  }
  FillVector<std::array<std::uint32_t, 3>> tris;
  assemble(direct, regions, slots, slot, count, override_regions, overrides, sources, tris, out.provenance);
  // The direct triangles' rounded corners are exact when grid points are
  // (Quantizer::grid_points_exact): none of them can round to zero area.
  write_indexed_mesh(
      tris, verts.exact.size(), [&](std::uint32_t v) { return verts.rounded[v]; },
      q.grid_points_exact() ? direct.tris.size() : 0, out.mesh, out.stats.rounded_degenerate);
  out.stats.triangulate_ms = ms_since(clock);
  return out;
}

}  // namespace ember::core
