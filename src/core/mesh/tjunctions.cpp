// Step 2 of the mesh stage: insert every output vertex that lies in the open
// interior of a polygon edge into that edge.
//
// Only the end points of edges whose uses do not balance are candidates. Why
// that suffices: the exact result's boundary is a cycle, so at every point of
// a line the edges covering it run as often one way as the other. Edges that
// join the same two ids a->b as often as b->a contribute nothing anywhere, so
// the unbalanced edges alone cancel along every line; split at all of their
// own end points, they become sub-edges between consecutive such points,
// which therefore balance id pair by id pair. Every edge, balanced or not, is
// tested against the candidates, so an end point that lies inside a balanced
// pair (a non-manifold line, where more sheets meet) is inserted there too.
// On a typical result a few percent of the vertices are candidates, which
// keeps the search cheap: most queries find an empty cell.
//
// Candidates come from the rounded positions: rounding is correctly rounded
// and hence monotone per coordinate, so a point exactly between two others
// rounds into the box of their rounded positions (no epsilon needed). Each
// candidate is then tested exactly: on the support plane and the edge plane,
// and strictly inside the neighbouring edge planes (which cross the edge's
// line exactly at its end points).
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_sort.h>

#include <algorithm>
#include <cmath>

#include "core/mesh/mesh_output.hpp"
#include "core/mesh/vertex_index.hpp"
#include "ember/geometry/exact_order.hpp"

namespace ember::core {

namespace {

double mean_edge_length(std::span<const OutputPolygon> polys, const OutputVertices& verts) {
  double sum = 0;
  std::size_t count = 0;
  const std::size_t stride = std::max<std::size_t>(1, polys.size() / 4096);
  for (std::size_t p = 0; p < polys.size(); p += stride) {
    const auto c = verts.corners[p];
    for (std::size_t k = 0; k < c.size(); ++k) {
      const Vec3d& a = verts.rounded[c[k]];
      const Vec3d& b = verts.rounded[c[(k + 1) % c.size()]];
      sum += std::max({std::fabs(a.x - b.x), std::fabs(a.y - b.y), std::fabs(a.z - b.z)});
      ++count;
    }
  }
  return count ? sum / static_cast<double>(count) : 1.0;
}

/// Vertices strictly inside edge k of polygon op, ordered from its start.
/// An unbuilt triangle's edge planes are built (into `scratch`) only when the
/// search finds a candidate: most edges have none.
void edge_interior_vertices(const OutputPolygon& op, std::span<const std::uint32_t> ids, std::size_t k,
                            const OutputVertices& verts, const VertexIndex& index, Polygon& scratch,
                            std::vector<std::uint32_t>& found) {
  const std::size_t n = ids.size();
  const std::uint32_t a = ids[k], b = ids[(k + 1) % n];
  const Vec3d &ra = verts.rounded[a], &rb = verts.rounded[b];
  const Polygon* poly = op.corners ? nullptr : &op.poly;
  found.clear();
  index.for_each_near_segment(ra, rb, [&](std::uint32_t v) {
    if (v == a || v == b) return;
    if (!poly) {
      const std::array<IntPoint, 3>& c = *op.corners;
      assign_triangle(c[0], c[1], c[2], scratch);  // corners k, k+1 are ids k, k+1: same order
      poly = &scratch;
    }
    const Plane& edge = poly->edges[k];
    const Plane& before = poly->edges[(k + n - 1) % n];  // crosses the edge's line at a
    const Plane& after = poly->edges[(k + 1) % n];       // crosses it at b
    const Point& x = verts.exact[v];
    if (classify(x, poly->support) != 0 || classify(x, edge) != 0) return;
    if (classify(x, before) < 0 && classify(x, after) < 0) found.push_back(v);
  });
  if (found.size() < 2) return;
  std::sort(found.begin(), found.end());
  found.erase(std::unique(found.begin(), found.end()), found.end());
  // Points on one line are ordered alike by any coordinate in which the end points differ.
  int axis = 0;
  while (axis < 2 && compare_coord(verts.exact[a], verts.exact[b], axis) == 0) ++axis;
  const bool ascending = compare_coord(verts.exact[a], verts.exact[b], axis) < 0;
  std::sort(found.begin(), found.end(), [&](std::uint32_t x, std::uint32_t y) {
    const int c = compare_coord(verts.exact[x], verts.exact[y], axis);
    return ascending ? c < 0 : c > 0;
  });
}


/// The corner edges (corner c runs from corners.ids[c] to the next corner of
/// its polygon) grouped by undirected id pair: every edge of a pair is the
/// same segment, so it is searched once.
struct EdgePairs {
  std::vector<std::uint32_t> corner;     ///< corners sorted by (pair, corner)
  std::vector<std::uint32_t> run_begin;  ///< pair r owns corner[run_begin[r] .. run_begin[r+1])
  std::vector<std::uint32_t> run_of;     ///< per corner: its pair
  std::vector<std::uint32_t> poly_of;    ///< per corner: its polygon
};

EdgePairs group_edges_by_pair(const Cycles& corners) {
  const std::size_t n = corners.ids.size();
  EdgePairs g;
  g.poly_of.resize(n);
  std::vector<std::pair<std::uint64_t, std::uint32_t>> keyed(n);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, corners.size(), 256), [&](const auto& r) {
    for (std::size_t p = r.begin(); p != r.end(); ++p) {
      const auto ids = corners[p];
      for (std::size_t k = 0; k < ids.size(); ++k) {
        const std::uint64_t a = ids[k], b = ids[(k + 1) % ids.size()];
        const auto c = static_cast<std::uint32_t>(corners.offsets[p] + k);
        keyed[c] = {(std::min(a, b) << 32) | std::max(a, b), c};
        g.poly_of[c] = static_cast<std::uint32_t>(p);
      }
    }
  });
  tbb::parallel_sort(keyed.begin(), keyed.end());
  g.corner.resize(n);
  g.run_of.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    if (i == 0 || keyed[i].first != keyed[i - 1].first) g.run_begin.push_back(static_cast<std::uint32_t>(i));
    g.corner[i] = keyed[i].second;
    g.run_of[keyed[i].second] = static_cast<std::uint32_t>(g.run_begin.size() - 1);
  }
  g.run_begin.push_back(static_cast<std::uint32_t>(n));
  return g;
}

}  // namespace

VertexIndex index_output_vertices(std::span<const OutputPolygon> polys, const OutputVertices& verts) {
  std::vector<std::uint32_t> everyone(verts.exact.size());
  for (std::uint32_t v = 0; v < everyone.size(); ++v) everyone[v] = v;
  return VertexIndex(verts.rounded, std::move(everyone), mean_edge_length(polys, verts));
}

Cycles insert_tjunction_vertices(std::span<const OutputPolygon> polys, const OutputVertices& verts,
                                 const VertexIndex& index, std::size_t& inserted) {
  const Cycles& corners = verts.corners;
  const EdgePairs pairs = group_edges_by_pair(corners);
  // Per pair: the vertices inside its segment, ordered from the pair's first
  // corner's start vertex (most pairs have none and allocate nothing).
  const std::size_t runs = pairs.run_begin.size() - 1;
  std::vector<std::vector<std::uint32_t>> inside(runs);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, runs, 256), [&](const auto& r) {
    std::vector<std::uint32_t> found;
    Polygon scratch;
    for (std::size_t run = r.begin(); run != r.end(); ++run) {
      const std::uint32_t c = pairs.corner[pairs.run_begin[run]], p = pairs.poly_of[c];
      const auto ids = corners[p];
      if (ids[c - corners.offsets[p]] == ids[(c - corners.offsets[p] + 1) % ids.size()]) continue;
      edge_interior_vertices(polys[p], ids, c - corners.offsets[p], verts, index, scratch, found);
      if (!found.empty()) inside[run] = found;
    }
  });
  // Only polygons that gain a vertex get a cycle of their own.
  std::vector<std::vector<std::uint32_t>> grown(polys.size());
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, polys.size(), 256), [&](const auto& r) {
    std::vector<std::uint32_t> cycle;
    for (std::size_t p = r.begin(); p != r.end(); ++p) {
      const auto ids = corners[p];
      cycle.clear();
      for (std::size_t k = 0; k < ids.size(); ++k) {
        cycle.push_back(ids[k]);
        const std::uint32_t run = pairs.run_of[corners.offsets[p] + k];
        const std::vector<std::uint32_t>& in = inside[run];
        if (in.empty()) continue;
        // Same start as the searched edge: same order; else the edge runs the other way.
        if (corners.ids[pairs.corner[pairs.run_begin[run]]] == ids[k]) {
          cycle.insert(cycle.end(), in.begin(), in.end());
        } else {
          cycle.insert(cycle.end(), in.rbegin(), in.rend());
        }
      }
      if (cycle.size() > ids.size()) grown[p] = cycle;
    }
  });
  Cycles out;
  out.offsets.resize(polys.size() + 1, 0);
  for (std::size_t p = 0; p < polys.size(); ++p)
    out.offsets[p + 1] = out.offsets[p] + static_cast<std::uint32_t>(grown[p].empty() ? corners[p].size() : grown[p].size());
  out.ids.resize(out.offsets.back());
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, polys.size(), 256), [&](const auto& r) {
    for (std::size_t p = r.begin(); p != r.end(); ++p) {
      const auto from = grown[p].empty() ? corners[p] : std::span<const std::uint32_t>(grown[p]);
      std::copy(from.begin(), from.end(), out.ids.begin() + out.offsets[p]);
    }
  });
  inserted = out.ids.size() - verts.corners.ids.size();
  return out;
}

}  // namespace ember::core
