// Step 2 of the mesh stage: insert every output vertex that lies in the open
// interior of a polygon edge into that edge.
//
// Every output vertex is a candidate for every edge. The end points of edges
// whose uses do not balance would be enough for a balanced (closed) mesh: the
// exact result's boundary is a cycle, so along every line the unbalanced
// edges alone cancel, and split at all of their own end points they balance
// id pair by id pair. But a vertex where another sheet touches an edge (a
// non-manifold contact: an apex resting on an edge, even one between two
// whole input triangles) is no such end point, and it must be inserted too
// for the mesh to have no vertex inside any edge.
//
// Candidates come from the rounded positions: rounding is correctly rounded
// and hence monotone per coordinate, so a point exactly between two others
// rounds into the box of their rounded positions (no epsilon needed). A
// floating-point filter with a proven margin (clearly_off_segment) drops the
// ones that are plainly off the line; the rest are tested exactly: on the
// support plane, collinear with the edge's end points in the plane's
// projection, and strictly between them.
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>

#include "core/mesh/mesh_output.hpp"
#include "core/mesh/vertex_index.hpp"
#include "core/sort_pairs.hpp"
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

/// Vertices strictly inside the edge from id a to id b of a polygon in
/// `support`, ordered from a. Needs no edge planes (output polygons do not
/// keep them): a candidate lies on the edge iff it is on the support plane,
/// collinear with a and b in the plane's projection along its dominant axis
/// (one-to-one on the plane), and strictly between them along an axis in
/// which they differ. Candidates are rare, so the exact tests on the welded
/// points cost little.
void edge_interior_vertices(const Plane& support, std::uint32_t a, std::uint32_t b, const OutputVertices& verts,
                            const VertexIndex& index, std::vector<std::uint32_t>& found) {
  const Point &pa = verts.exact[a], &pb = verts.exact[b];
  // Points on one line are ordered alike by any coordinate in which the end
  // points differ: found on the first collinear candidate (most edges have none).
  int axis = -1, dir = 0;
  found.clear();
  index.for_each_near_segment(verts.rounded[a], verts.rounded[b], [&](std::uint32_t v) {
    if (v == a || v == b || clearly_off_segment(verts.rounded[a], verts.rounded[b], verts.rounded[v])) return;
    const Point& x = verts.exact[v];
    if (classify(x, support) != 0 || orient2d_dropped(pa, pb, x, dominant_axis(support)) != 0) return;
    if (axis < 0) {
      axis = 0;
      while (axis < 2 && compare_coord(pa, pb, axis) == 0) ++axis;
      dir = compare_coord(pa, pb, axis);  // a != b: not 0
    }
    if (compare_coord(pa, x, axis) == dir && compare_coord(x, pb, axis) == dir) found.push_back(v);
  });
  if (found.size() < 2) return;
  std::sort(found.begin(), found.end());
  found.erase(std::unique(found.begin(), found.end()), found.end());
  std::sort(found.begin(), found.end(), [&](std::uint32_t x, std::uint32_t y) {
    const int c = compare_coord(verts.exact[x], verts.exact[y], axis);
    return dir < 0 ? c < 0 : c > 0;
  });
}


}  // namespace

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
  sort_pairs(keyed);
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


VertexIndex index_output_vertices(std::span<const OutputPolygon> polys, const OutputVertices& verts) {
  std::vector<std::uint32_t> everyone(verts.exact.size());
  for (std::uint32_t v = 0; v < everyone.size(); ++v) everyone[v] = v;
  return VertexIndex(verts.rounded, std::move(everyone), mean_edge_length(polys, verts));
}

Cycles insert_tjunction_vertices(std::span<const OutputPolygon> polys, const OutputVertices& verts,
                                 const VertexIndex& index, const EdgePairs& pairs, std::size_t& inserted) {
  const Cycles& corners = verts.corners;
  // Per pair: the vertices inside its segment, ordered from the pair's first
  // corner's start vertex (most pairs have none and allocate nothing).
  const std::size_t runs = pairs.run_begin.size() - 1;
  std::vector<std::vector<std::uint32_t>> inside(runs);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, runs, 256), [&](const auto& r) {
    std::vector<std::uint32_t> found;
    for (std::size_t run = r.begin(); run != r.end(); ++run) {
      const std::uint32_t c = pairs.corner[pairs.run_begin[run]], p = pairs.poly_of[c];
      const auto ids = corners[p];
      const std::uint32_t a = ids[c - corners.offsets[p]], b = ids[(c - corners.offsets[p] + 1) % ids.size()];
      if (a == b) continue;
      edge_interior_vertices(support_of(polys[p]), a, b, verts, index, found);
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
