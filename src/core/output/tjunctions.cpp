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
#include "core/output/tjunctions.hpp"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <atomic>
#include <cmath>

#include "core/output/output_vertices.hpp"
#include "core/output/vertex_index.hpp"
#include "core/support/sort_pairs.hpp"
#include "geometry/exact_order.hpp"

namespace ember::core {

namespace {

double mean_edge_length(std::span<const OutputPolygon> polys, const OutputVertices& verts) {
  double sum = 0;
  std::size_t count = 0;
  const std::size_t stride = std::max<std::size_t>(1, polys.size() / 4096);
  for (std::size_t p = 0; p < polys.size(); p += stride) {
    if (polys[p].settled) continue;
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
                            const VertexIndex& index, VertexIndex::Part part, std::vector<std::uint32_t>& found) {
  const Point &pa = verts.exact[a], &pb = verts.exact[b];
  // Points on one line are ordered alike by any coordinate in which the end
  // points differ: found on the first collinear candidate (most edges have none).
  int axis = -1, dir = 0;
  found.clear();
  const SegmentFilter near(verts.rounded[a], verts.rounded[b]);
  index.for_each_near_segment(
      verts.rounded[a], verts.rounded[b],
      [&](std::uint32_t v) {
        if (v == a || v == b || near.clearly_off(verts.rounded[v])) return;
        const Point& x = verts.exact[v];
        if (classify(x, support) != 0 || orient2d_dropped(pa, pb, x, dominant_axis(support)) != 0) return;
        if (axis < 0) {
          axis = 0;
          while (axis < 2 && compare_coord(pa, pb, axis) == 0) ++axis;
          dir = compare_coord(pa, pb, axis);  // a != b: not 0
        }
        if (compare_coord(pa, x, axis) == dir && compare_coord(x, pb, axis) == dir) found.push_back(v);
      },
      part);
  if (found.size() < 2) return;
  std::sort(found.begin(), found.end());
  found.erase(std::unique(found.begin(), found.end()), found.end());
  std::sort(found.begin(), found.end(), [&](std::uint32_t x, std::uint32_t y) {
    const int c = compare_coord(verts.exact[x], verts.exact[y], axis);
    return dir < 0 ? c < 0 : c > 0;
  });
}

/// The operand o when pair `run` is the edge between exactly two whole
/// input triangles of solid operand o, on a manifold edge of o; -1
/// otherwise. Then no other polygon of o has a vertex inside the edge: its
/// triangle would meet one of the two beyond a shared vertex or edge (the
/// proof rules that out) or share the edge (a third use: not manifold). Both
/// uses being unbuilt triangles of o on the same two points, the second one
/// is the edge's other input use, so one manifold bit decides.
int whole_solid_edge(std::size_t run, std::span<const OutputPolygon> polys, const Cycles& corners,
                     const EdgePairs& pairs, const InputTopology& topology) {
  const std::uint32_t first = pairs.run_begin[run];
  if (pairs.run_begin[run + 1] - first != 2) return -1;
  const std::uint32_t c = pairs.corner[first];
  const std::uint32_t p = pairs.poly_of[c], q = pairs.poly_of[pairs.corner[first + 1]];
  const OutputPolygon &a = polys[p], &b = polys[q];
  if (!unbuilt(a) || !unbuilt(b) || a.operand != b.operand || !topology.solid[a.operand]) return -1;
  const std::uint32_t k = c - corners.offsets[p];  // an unbuilt triangle's corner k is its grid corner k
  return (topology.manifold_edges[a.id] >> k) & 1u ? static_cast<int>(a.operand) : -1;
}

}  // namespace

EdgePairs group_edges_by_pair(const Cycles& corners, std::span<const OutputPolygon> polys) {
  const auto settled = [&](std::size_t p) { return !polys.empty() && polys[p].settled; };
  // Corners of settled polygons are left out (their run_of is kNoRun): the
  // kept ones first get their slot in `keyed` by a prefix count.
  std::vector<std::uint32_t> slot(corners.size() + 1, 0);
  for (std::size_t p = 0; p < corners.size(); ++p)
    slot[p + 1] = slot[p] + (settled(p) ? 0 : static_cast<std::uint32_t>(corners[p].size()));
  const std::size_t n = slot.back();
  EdgePairs g;
  g.poly_of.resize(corners.ids.size());
  g.run_of.assign(corners.ids.size(), EdgePairs::kNoRun);
  FillVector<std::pair<std::uint64_t, std::uint32_t>> keyed(n);  // every slot written below
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, corners.size(), 256), [&](const auto& r) {
    for (std::size_t p = r.begin(); p != r.end(); ++p) {
      const auto ids = corners[p];
      for (std::size_t k = 0; k < ids.size(); ++k) {
        const auto c = static_cast<std::uint32_t>(corners.offsets[p] + k);
        g.poly_of[c] = static_cast<std::uint32_t>(p);
        if (settled(p)) continue;
        const std::uint64_t a = ids[k], b = ids[(k + 1) % ids.size()];
        keyed[slot[p] + k] = {(std::min(a, b) << 32) | std::max(a, b), c};
      }
    }
  });
  sort_pairs(keyed);
  g.corner.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    if (i == 0 || keyed[i].first != keyed[i - 1].first) g.run_begin.push_back(static_cast<std::uint32_t>(i));
    g.corner[i] = keyed[i].second;
    g.run_of[keyed[i].second] = static_cast<std::uint32_t>(g.run_begin.size() - 1);
  }
  g.run_begin.push_back(static_cast<std::uint32_t>(n));
  return g;
}

namespace {
/// Whether index_output_vertices orders cells by operand (and step 2 uses it).
bool search_by_operand(const InputTopology* topology) {
  return topology && topology->solid.size() == 2 && !topology->manifold_edges.empty() &&
         (topology->solid[0] || topology->solid[1]);
}
}  // namespace

VertexIndex index_output_vertices(std::span<const OutputPolygon> polys, const OutputVertices& verts,
                                  const InputTopology* topology) {
  // Vertices only settled polygons use lie inside no edge (OutputPolygon::settled).
  std::vector<char> wanted(verts.exact.size(), 0);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, polys.size(), 1024), [&](const auto& r) {
    for (std::size_t p = r.begin(); p != r.end(); ++p)
      if (!polys[p].settled)
        for (const std::uint32_t v : verts.corners[p])
          std::atomic_ref<char>(wanted[v]).store(1, std::memory_order_relaxed);
  });
  std::vector<std::uint32_t> everyone;
  for (std::uint32_t v = 0; v < wanted.size(); ++v)
    if (wanted[v]) everyone.push_back(v);
  const double cell = mean_edge_length(polys, verts);
  if (!search_by_operand(topology)) return VertexIndex(verts.rounded, std::move(everyone), cell);
  // Bit o of used_by[v]: some polygon of operand o has v as a corner. Class
  // 0: used by operand 1 only, 1: by both, 2: by operand 0 only; the vertices
  // of operand 1's polygons are then classes 0-1 (Part::kLow), operand 0's
  // classes 1-2 (Part::kHigh).
  // Settled polygons are left out: a vertex only they use is no member, and
  // no other operand's polygon touches one (OutputPolygon::settled), so the
  // other users of its corners are of its own operand.
  std::vector<std::uint8_t> used_by(verts.exact.size(), 0);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, polys.size(), 1024), [&](const auto& r) {
    for (std::size_t p = r.begin(); p != r.end(); ++p)
      if (!polys[p].settled)
        for (const std::uint32_t v : verts.corners[p])
          std::atomic_ref<std::uint8_t>(used_by[v])
              .fetch_or(static_cast<std::uint8_t>(1u << polys[p].operand), std::memory_order_relaxed);
  });
  constexpr std::uint8_t kClass[4] = {0, 2, 0, 1};  // by used_by; 0 (unused) cannot occur
  std::vector<std::uint8_t> member_class(everyone.size());
  for (std::size_t i = 0; i < everyone.size(); ++i) member_class[i] = kClass[used_by[everyone[i]]];
  return VertexIndex(verts.rounded, std::move(everyone), cell, member_class);
}

Cycles insert_tjunction_vertices(std::span<const OutputPolygon> polys, const OutputVertices& verts,
                                 const VertexIndex& index, const EdgePairs& pairs, std::size_t& inserted,
                                 const InputTopology* topology) {
  const bool by_operand = search_by_operand(topology);
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
      // Only the other operand's vertices can lie inside an edge between two
      // whole triangles of a solid operand (whole_solid_edge).
      const int o = by_operand ? whole_solid_edge(run, polys, corners, pairs, *topology) : -1;
      using Part = VertexIndex::Part;
      const Part part = o < 0 ? Part::kAll : (o == 0 ? Part::kLow : Part::kHigh);
      edge_interior_vertices(support_of(polys[p]), a, b, verts, index, part, found);
      if (!found.empty()) inside[run] = found;
    }
  });
  // Only polygons that gain a vertex get a cycle of their own (never a
  // settled one: its edges were not searched).
  std::vector<std::vector<std::uint32_t>> grown(polys.size());
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, polys.size(), 256), [&](const auto& r) {
    std::vector<std::uint32_t> cycle;
    for (std::size_t p = r.begin(); p != r.end(); ++p) {
      if (polys[p].settled) continue;
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
    out.offsets[p + 1] =
        out.offsets[p] + static_cast<std::uint32_t>(grown[p].empty() ? corners[p].size() : grown[p].size());
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
