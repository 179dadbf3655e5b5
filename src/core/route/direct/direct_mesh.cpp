// The direct route of the solid path (see direct_mesh.hpp for the argument).
#include "core/route/direct/direct_mesh.hpp"

#include "core/route/direct/direct_faces.hpp"
#include "core/support/parallel_select.hpp"
#include "core/support/sort_pairs.hpp"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cassert>
#include <chrono>
#include <numeric>
#include <optional>
#include <tuple>

namespace ember::core {

std::optional<MeshOutput> direct_solid_mesh(const GridTriangles& grid, const Box& box, const SolveContext& ctx,
                                            const OperandTrees& trees, const Partners& partners, const Quantizer& q,
                                            std::span<const Provenance> sources, const InputTopology& topology,
                                            const std::atomic<bool>& stop) {
  if (ctx.operands != 2 || topology.operand_base.size() != 3) return std::nullopt;
  assert(grid.normals.size() == grid.corners.size());
  const auto clock = std::chrono::steady_clock::now();
  const std::size_t n = grid.corners.size();
  // Two operands (above); both lists in parallel (as serial passes over
  // every triangle they were a few ms of one thread on large inputs).
  FillVector<std::uint32_t> operand_of(n);  // every entry written here
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, 16384), [&](const auto& range) {
    for (std::size_t i = range.begin(); i != range.end(); ++i) operand_of[i] = i < trees.begin[1] ? 0 : 1;
  });
  const FillVector<std::uint32_t> touched =
      parallel_indices_where(n, [&](std::size_t i) { return partners.touched(static_cast<std::uint32_t>(i)); });
  // Each meeting pair's chord once, by its smaller triangle x (computing it
  // in each triangle, with its orientations and crossing points, was half of
  // the cutting). The chords of x = touched[i] with its partners above x
  // are chords[chord_at[i] ..], in partner order: one slot per pair.
  std::atomic<bool> failed{false};
  const EdgeNames names{topology, operand_of};
  // above[i]: where touched[i]'s partners above it begin in its (ascending) list.
  std::vector<std::uint32_t> above(touched.size());
  std::vector<std::size_t> chord_at(touched.size() + 1, 0);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, touched.size(), 1024), [&](const auto& range) {
    for (std::size_t i = range.begin(); i != range.end(); ++i) {
      const std::span<const std::uint32_t> l = partners.of(touched[i]);
      above[i] = static_cast<std::uint32_t>(std::upper_bound(l.begin(), l.end(), touched[i]) - l.begin());
      chord_at[i + 1] = l.size() - above[i];
    }
  });
  std::inclusive_scan(chord_at.begin(), chord_at.end(), chord_at.begin());
  FillVector<PairChord> chords(chord_at.back());  // every slot written below (or the route declines)
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, touched.size(), 64), [&](const auto& range) {
    for (std::size_t i = range.begin(); i != range.end() && !failed.load(std::memory_order_relaxed); ++i) {
      const std::span<const std::uint32_t> l = partners.of(touched[i]);
      for (std::size_t k = above[i]; k < l.size(); ++k)
        if (!pair_chord(grid, names, touched[i], l[k], chords[chord_at[i] + k - above[i]])) {
          failed = true;
          break;
        }
    }
  });
  if (failed.load() || stop.load()) return std::nullopt;
  // touched[i]'s chords as it sees them: its own slots for partners above
  // it, the partner's slot (found by two searches) for those below.
  const auto chord_refs = [&](std::size_t i, std::vector<ChordRef>& refs) {
    const std::uint32_t t = touched[i];
    const std::span<const std::uint32_t> l = partners.of(t);
    refs.clear();
    for (std::size_t k = 0; k < l.size(); ++k) {
      const std::uint32_t f = l[k];
      if (k >= above[i]) {
        refs.push_back({&chords[chord_at[i] + k - above[i]], t, f, false});
        continue;
      }
      const auto j = std::lower_bound(touched.begin(), touched.end(), f);
      const std::span<const std::uint32_t> lf = partners.of(f);
      const auto at = std::lower_bound(lf.begin(), lf.end(), t);
      if (j == touched.end() || *j != f || at == lf.end() || *at != t)
        return false;  // partners are mutual: not reached
      const std::size_t jf = static_cast<std::size_t>(j - touched.begin());
      refs.push_back({&chords[chord_at[jf] + static_cast<std::size_t>(at - lf.begin()) - above[jf]], f, t, true});
    }
    return true;
  };
  // Touched triangles in fixed blocks, each block's output in id order: the
  // result does not depend on the schedule.
  constexpr std::size_t kBlock = 64;
  std::vector<CutFaces> blocks((touched.size() + kBlock - 1) / kBlock);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, blocks.size(), 1), [&](const auto& range) {
    TriangleCutter cutter(grid, ctx, operand_of);
    std::vector<ChordRef> refs;
    for (std::size_t b = range.begin(); b != range.end() && !failed.load(std::memory_order_relaxed); ++b)
      for (std::size_t i = b * kBlock; i < std::min(touched.size(), (b + 1) * kBlock); ++i)
        if (!chord_refs(i, refs) || !cutter.cut(touched[i], refs, blocks[b])) {
          failed = true;
          break;
        }
  });
  if (failed.load() || stop.load()) return std::nullopt;
  const std::optional<FillVector<KeptTriangle>> untouched = solid_untouched(grid, box, ctx, trees, partners, stop);
  if (!untouched) return std::nullopt;

  // One vertex per name: input vertices keep their global ids, crossing
  // points follow in the order of their names.
  const std::uint32_t inputs = topology.operand_base.back();
  std::vector<std::size_t> name_at(blocks.size() + 1, 0);
  for (std::size_t b = 0; b < blocks.size(); ++b) name_at[b + 1] = name_at[b] + blocks[b].names.size();
  // The occurrences in (name, occurrence) order: by the name's edge in a
  // radix sort, then each run of one edge by (face, occurrence) (runs are
  // short, and a comparison sort of all the names spends many steps per
  // element).
  std::vector<CrossingName> name_of(name_at.back());
  FillVector<std::pair<std::uint64_t, std::uint32_t>> named(name_at.back());  // (edge, global occurrence)
  tbb::parallel_for(std::size_t{0}, blocks.size(), [&](std::size_t b) {
    for (std::size_t i = 0; i < blocks[b].names.size(); ++i) {
      name_of[name_at[b] + i] = blocks[b].names[i];
      named[name_at[b] + i] = {blocks[b].names[i].edge, static_cast<std::uint32_t>(name_at[b] + i)};
    }
  });
  sort_pairs(named);
  sort_equal_key_runs(
      named, [&](const std::pair<std::uint64_t, std::uint32_t>& a, const std::pair<std::uint64_t, std::uint32_t>& b) {
        const std::uint32_t fa = name_of[a.second].face, fb = name_of[b.second].face;
        return fa != fb ? fa < fb : a.second < b.second;
      });
  std::vector<std::uint32_t> id_of(named.size());
  std::vector<std::uint32_t> first_of;  // per crossing vertex: its first occurrence
  for (std::size_t i = 0; i < named.size(); ++i) {
    if (i == 0 || name_of[named[i].second] != name_of[named[i - 1].second]) first_of.push_back(named[i].second);
    id_of[named[i].second] = inputs + static_cast<std::uint32_t>(first_of.size() - 1);
  }
  std::vector<const Point*> point_of(named.size());
  for (std::size_t b = 0; b < blocks.size(); ++b)
    for (std::size_t i = 0; i < blocks[b].points.size(); ++i) point_of[name_at[b] + i] = &blocks[b].points[i];
  std::vector<Vec3d> crossing_rounded(first_of.size());
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, first_of.size(), 256), [&](const auto& range) {
    for (std::size_t v = range.begin(); v != range.end(); ++v) {
      const Vec3d x = q.dequantize(*point_of[first_of[v]]);
      crossing_rounded[v] = {x.x + 0.0, x.y + 0.0, x.z + 0.0};  // -0.0 -> +0.0
    }
  });

  // The triangles: kept untouched ones by id, then the touched ones' faces.
  const auto vertex = [&](std::uint32_t t, std::size_t k) {
    return topology.operand_base[operand_of[t]] + topology.by_triangle[t][k];
  };
  std::vector<std::size_t> tri_at(blocks.size() + 1, untouched->size());
  for (std::size_t b = 0; b < blocks.size(); ++b) tri_at[b + 1] = tri_at[b] + blocks[b].tris.size();
  FillVector<std::array<std::uint32_t, 3>> tris(tri_at.back());  // every entry written below
  MeshOutput out;
  reserve_touched(out.provenance, tris.size());  // its pages faulted in parallel before the serial resize
  out.provenance.resize(tris.size());
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, untouched->size(), 1024), [&](const auto& range) {
    for (std::size_t i = range.begin(); i != range.end(); ++i) {
      const KeptTriangle& p = (*untouched)[i];
      tris[i] = {vertex(p.id, 0), vertex(p.id, p.flip ? 2 : 1), vertex(p.id, p.flip ? 1 : 2)};
      out.provenance[i] = sources[p.id];
    }
  });
  tbb::parallel_for(std::size_t{0}, blocks.size(), [&](std::size_t b) {
    const CutFaces& block = blocks[b];
    for (std::size_t i = 0; i < block.tris.size(); ++i) {
      std::array<std::uint32_t, 3>& t = tris[tri_at[b] + i];
      for (std::size_t k = 0; k < 3; ++k) {
        const std::uint32_t v = block.tris[i][k];
        t[k] = v < 3 ? vertex(block.source[i], v) : id_of[name_at[b] + v - 3];
      }
      out.provenance[tri_at[b] + i] = sources[block.source[i]];
    }
  });
  // Where each input vertex is: any corner that names it (all are the same point).
  FillVector<std::uint32_t> corner_of = parallel_filled<std::uint32_t>(inputs, 0);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, 4096), [&](const auto& range) {
    for (std::size_t t = range.begin(); t != range.end(); ++t)
      for (std::size_t k = 0; k < 3; ++k)
        std::atomic_ref<std::uint32_t>(corner_of[vertex(static_cast<std::uint32_t>(t), k)])
            .store(static_cast<std::uint32_t>(3 * t + k), std::memory_order_relaxed);
  });
  const auto position = [&](std::uint32_t v) {
    if (v >= inputs) return crossing_rounded[v - inputs];
    return q.dequantize(grid.corners[corner_of[v] / 3][corner_of[v] % 3]);
  };
  write_indexed_mesh(tris, inputs + first_of.size(), position, q.grid_points_exact() ? untouched->size() : 0, out.mesh,
                     out.stats.rounded_degenerate);
  for (const CutFaces& block : blocks) out.stats.regions += block.faces;
  out.stats.triangulate_ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - clock).count();
  return out;
}

}  // namespace ember::core
