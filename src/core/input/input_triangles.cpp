// Validation, closedness and the grid triangles by id (see input_triangles.hpp).
#include "core/input/input_triangles.hpp"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_reduce.h>
#include <tbb/parallel_scan.h>

#include <atomic>
#include <cmath>
#include <limits>
#include <optional>
#include <string>

#include "core/input/edge_matching.hpp"
#include "ember/error.hpp"

namespace ember::core {

namespace {

/// What is wrong with face f, or nothing. Only for offsets already known to
/// be non-decreasing (then every face's span lies inside `indices`).
std::optional<std::string> face_problem(const Mesh& m, std::size_t f) {
  if (m.face_size(f) < 3)
    return "face " + std::to_string(f) + " has " + std::to_string(m.face_size(f)) + " vertices; faces need at least 3";
  for (const std::uint32_t v : m.face(f))
    if (v >= m.vertices.size())
      return "face " + std::to_string(f) + " uses vertex index " + std::to_string(v) + ", but the mesh has " +
             std::to_string(m.vertices.size()) + " vertices";
  return std::nullopt;
}

bool finite(const Vec3d& p) { return std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z); }

/// The lowest i in [0, n) with bad(i), or n: parallel, the answer does not
/// depend on the split.
template <typename Bad>
std::size_t first_bad(std::size_t n, Bad&& bad) {
  std::atomic<std::size_t> first{n};
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, 2048), [&](const tbb::blocked_range<std::size_t>& r) {
    for (std::size_t i = r.begin(); i != r.end() && i < first.load(std::memory_order_relaxed); ++i)
      if (bad(i)) {
        std::size_t seen = first.load(std::memory_order_relaxed);
        while (i < seen && !first.compare_exchange_weak(seen, i, std::memory_order_relaxed)) {
        }
        return;
      }
  });
  return first.load();
}

/// Whether every face has at least 3 corners (so the offsets increase) and
/// every index names a vertex: two flat passes without branches per face,
/// a fraction of the per-face search below, which then only runs to name
/// the first problem of a mesh that has one.
bool faces_valid(const Mesh& m) {
  const auto all = [](std::size_t n, auto&& ok) {
    return tbb::parallel_reduce(
        tbb::blocked_range<std::size_t>(0, n, 8192), true,
        [&](const tbb::blocked_range<std::size_t>& r, bool good) {
          bool here = true;
          for (std::size_t i = r.begin(); i != r.end(); ++i) here &= ok(i);
          return good && here;
        },
        [](bool a, bool b) { return a && b; });
  };
  const std::uint32_t* off = m.face_offsets.data();
  const std::uint32_t* idx = m.indices.data();
  const std::size_t vertices = m.vertices.size();
  return all(m.face_count(), [&](std::size_t f) { return off[f + 1] >= off[f] && off[f + 1] - off[f] >= 3; }) &&
         all(m.indices.size(), [&](std::size_t i) { return idx[i] < vertices; });
}

}  // namespace

void validate_operands(std::span<const Mesh> operands) {
  for (std::size_t o = 0; o < operands.size(); ++o) {
    const Mesh& m = operands[o];
    if (m.face_offsets.empty() || m.face_offsets.front() != 0 || m.face_offsets.back() != m.indices.size())
      throw Error("face_offsets must start at 0 and end at indices.size()", {.operand = o});
    if (!faces_valid(m)) {  // find and name the first problem
      const std::size_t d =
          first_bad(m.face_count(), [&](std::size_t i) { return m.face_offsets[i + 1] < m.face_offsets[i]; });
      if (d < m.face_count())
        throw Error("face_offsets must not decrease (face " + std::to_string(d) + ")", {.operand = o, .face = d});
      const std::size_t f = first_bad(m.face_count(), [&](std::size_t i) { return face_problem(m, i).has_value(); });
      if (f < m.face_count()) throw Error(*face_problem(m, f), {.operand = o, .face = f});
    }
    const std::size_t v = first_bad(m.vertices.size(), [&](std::size_t i) { return !finite(m.vertices[i]); });
    if (v < m.vertices.size())
      throw Error("vertex " + std::to_string(v) + " has a non-finite coordinate (NaN or infinity); fix or remove it",
                  {.operand = o, .vertex = v});
  }
}

EdgeMatching match_edges(const GridInput& gi) {
  const std::size_t operands = gi.vertex_count.size();
  EdgeMatching m;
  const std::size_t n = gi.vertex_ids.size();
  m.open.assign(operands, 0);
  m.manifold.resize(n);
  m.partner.resize(n);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, 4096), [&](const tbb::blocked_range<std::size_t>& r) {
    for (std::size_t t = r.begin(); t != r.end(); ++t) m.partner[t] = {kNoNeighbor, kNoNeighbor, kNoNeighbor};
  });
  tbb::parallel_for(std::size_t{0}, operands, [&](std::size_t o) {
    const std::size_t begin = gi.operand_begin[o];
    WeldedTriangles welded;
    welded.ids = std::span(gi.vertex_ids).subspan(begin, gi.operand_begin[o + 1] - begin);
    welded.vertex_count = gi.vertex_count[o];
    // Called concurrently, but each directed edge use belongs to one
    // undirected edge: every partner slot has one writer.
    for_each_edge(welded, [&](std::span<const EdgeUse> uses) {
      int balance = 0;
      for (const EdgeUse& u : uses) balance += u.forward ? 1 : -1;
      if (balance != 0) std::atomic_ref<std::size_t>(m.open[o]).fetch_add(1, std::memory_order_relaxed);
      if (uses.size() != 2 || uses[0].forward == uses[1].forward) return;
      for (int i = 0; i < 2; ++i)
        m.partner[begin + uses[i].tri][uses[i].edge] = static_cast<std::uint32_t>(begin + uses[1 - i].tri);
    });
  });
  // The manifold bits are the edges that found a partner.
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, 4096), [&](const tbb::blocked_range<std::size_t>& r) {
    for (std::size_t t = r.begin(); t != r.end(); ++t) {
      std::uint8_t bits = 0;
      for (int e = 0; e < 3; ++e) bits |= static_cast<std::uint8_t>((m.partner[t][e] != kNoNeighbor) << e);
      m.manifold[t] = bits;
    }
  });
  return m;
}

InputTriangles build_grid_triangles(GridInput& gi, const EdgeMatching& edges) {
  const std::size_t n = gi.triangles.size();
  // Pass 1: which triangles have area (the exact grid normal is non-zero;
  // make_triangle decides the same).
  FillVector<std::uint32_t> id(n + 1);  // pass 1 writes id[1..n]
  id[0] = 0;
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, 4096), [&](const tbb::blocked_range<std::size_t>& r) {
    for (std::size_t i = r.begin(); i != r.end(); ++i)
      id[i + 1] = gi.normals[i] != std::array<std::int64_t, 3>{0, 0, 0};
  });
  // Ids in input order over the kept triangles: an exclusive prefix sum.
  static_assert(sizeof(std::uint32_t) == 4);
  if (n >= std::numeric_limits<std::uint32_t>::max()) throw Error("boolean: more than 2^32 - 1 input triangles");
  tbb::parallel_scan(
      tbb::blocked_range<std::size_t>(1, n + 1, 1 << 14), std::uint32_t{0},
      [&](const tbb::blocked_range<std::size_t>& r, std::uint32_t sum, bool final) {
        for (std::size_t i = r.begin(); i != r.end(); ++i) {
          sum += id[i];
          if (final) id[i] = sum;
        }
        return sum;
      },
      [](std::uint32_t a, std::uint32_t b) { return a + b; });
  InputTriangles in;
  const std::size_t kept = id[n];
  in.dropped_degenerate = n - kept;
  // GridInput holds the operands one after the other: so do the ids.
  in.operand_begin.resize(gi.operand_begin.size());
  for (std::size_t o = 0; o < gi.operand_begin.size(); ++o) in.operand_begin[o] = id[gi.operand_begin[o]];
  in.sources.resize(kept);
  // Most inputs drop nothing: then the arrays GridTriangles keeps are moved
  // out of gi, not copied (copies would hold both at the set-up's peak:
  // ~110 bytes per triangle).
  const bool keep_all = kept == n;
  if (keep_all) {
    in.grid.corners = std::move(gi.corners);
    in.grid.normals = std::move(gi.normals);
    in.grid.vertex_ids = std::move(gi.vertex_ids);
  } else {
    in.grid.corners.resize(kept);
    in.grid.normals.resize(kept);
    in.grid.vertex_ids.resize(kept);
  }
  in.grid.manifold_edges.resize(kept);
  in.grid.neighbors.resize(kept);
  // Pass 2: triangle i (kept when id[i + 1] > id[i]) becomes polygon id[i].
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, 1024), [&](const tbb::blocked_range<std::size_t>& r) {
    for (std::size_t i = r.begin(); i != r.end(); ++i) {
      if (id[i + 1] == id[i]) continue;
      const GridTriangle& t = gi.triangles[i];
      const std::uint32_t k = id[i];
      if (!keep_all) {
        in.grid.corners[k] = gi.corners[i];
        in.grid.normals[k] = gi.normals[i];
        in.grid.vertex_ids[k] = gi.vertex_ids[i];
      }
      in.sources[k] = {t.operand, t.face};
      in.grid.manifold_edges[k] = edges.manifold[i];
      for (int e = 0; e < 3; ++e) {
        // A partner the grid made degenerate is no polygon: no neighbour.
        const std::uint32_t q = edges.partner[i][e];
        in.grid.neighbors[k][e] = q != kNoNeighbor && id[q + 1] != id[q] ? id[q] : kNoNeighbor;
      }
    }
  });
  return in;
}

}  // namespace ember::core
