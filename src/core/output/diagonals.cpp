// Step 5b of the mesh stage: vertices inside the diagonals of a region's
// triangulation.
//
// Steps 2-4 make every boundary edge of every region meet its neighbours
// vertex for vertex. A diagonal (an edge the triangulation draws through the
// region) can still pass through a vertex: only where another part of the
// result touches the region's interior at that point (a non-manifold contact,
// e.g. a cone's apex resting on a face). Such a vertex is inserted into the
// diagonal and both triangles on it are split in two, so no vertex lies inside
// an output edge. Triangles of positive area stay positive: the new corner is
// strictly inside the old edge and the opposite corner is off its line.
#include "core/output/diagonals.hpp"

#include <algorithm>
#include <utility>

#include "core/output/output_vertices.hpp"
#include "core/output/regions.hpp"
#include "core/output/vertex_index.hpp"
#include "geometry/exact_order.hpp"

namespace ember::core {

namespace {

using Tri = std::array<std::uint32_t, 3>;

/// Vertices strictly inside the segment x-y in the region's plane, ordered from x.
std::vector<std::uint32_t> inside_segment(std::uint32_t x, std::uint32_t y, const Plane& plane,
                                          const OutputVertices& verts, const VertexIndex& index,
                                          const std::vector<char>& used) {
  const Point &px = verts.exact[x], &py = verts.exact[y];
  int axis = 0;
  while (axis < 2 && compare_coord(px, py, axis) == 0) ++axis;
  const int toward_y = compare_coord(py, px, axis);
  std::vector<std::uint32_t> found;
  const SegmentFilter near(verts.rounded[x], verts.rounded[y]);
  index.for_each_near_segment(verts.rounded[x], verts.rounded[y], [&](std::uint32_t v) {
    if (v == x || v == y || !used[v] || near.clearly_off(verts.rounded[v])) return;
    const Point& pv = verts.exact[v];
    if (classify(pv, plane) != 0 || orient_in_plane(px, py, pv, plane) != 0) return;
    // On the line: strictly between x and y along an axis in which they differ.
    if (compare_coord(pv, px, axis) == toward_y && compare_coord(py, pv, axis) == toward_y) found.push_back(v);
  });
  std::sort(found.begin(), found.end());
  found.erase(std::unique(found.begin(), found.end()), found.end());
  std::sort(found.begin(), found.end(), [&](std::uint32_t a, std::uint32_t b) {
    return compare_coord(verts.exact[b], verts.exact[a], axis) == toward_y;  // a comes first from x
  });
  return found;
}

/// Replaces triangle t, whose edge from corner k runs a -> b, by the fan
/// through the points strictly inside a-b (ordered from a).
void split_triangle(std::vector<Tri>& tris, std::size_t t, int k, const std::vector<std::uint32_t>& between) {
  const Tri old = tris[t];
  const std::uint32_t a = old[k], b = old[(k + 1) % 3], c = old[(k + 2) % 3];
  std::uint32_t from = a;
  for (std::size_t i = 0; i <= between.size(); ++i) {
    const std::uint32_t to = i < between.size() ? between[i] : b;
    const Tri piece{from, to, c};
    if (i == 0) {
      tris[t] = piece;
    } else {
      tris.push_back(piece);
    }
    from = to;
  }
}

}  // namespace

std::size_t split_diagonals(const Plane& plane, const OutputVertices& verts, const VertexIndex& index,
                            const std::vector<char>& used, std::vector<Tri>& tris) {
  if (tris.size() < 2) return 0;
  std::size_t inserted = 0;
  // New edges from a split point to an opposite corner are diagonals too;
  // repeat until a pass splits nothing (each split adds a vertex to the
  // triangulation, so this ends).
  struct Directed {
    std::uint32_t x, y;  ///< the edge x -> y
    std::uint32_t t;     ///< its triangle
    int k;               ///< its corner in t (the edge runs from corner k)
    bool operator<(const Directed& o) const { return x != o.x ? x < o.x : y < o.y; }
  };
  std::vector<Directed> directed;
  for (bool changed = true; changed;) {
    changed = false;
    directed.clear();
    for (std::size_t t = 0; t < tris.size(); ++t)
      for (int k = 0; k < 3; ++k)
        directed.push_back({tris[t][k], tris[t][(k + 1) % 3], static_cast<std::uint32_t>(t), k});
    // A valid triangulation uses each directed edge once; were one repeated,
    // its last use stands for it (as a map assigned in this order would keep).
    std::stable_sort(directed.begin(), directed.end());
    std::size_t kept = 0;
    for (std::size_t i = 0; i < directed.size(); ++i) {
      const bool last = i + 1 == directed.size() || directed[i] < directed[i + 1];
      if (last) directed[kept++] = directed[i];
    }
    directed.resize(kept);
    for (const Directed& e : directed) {
      if (e.x > e.y) continue;  // each diagonal once, from its smaller id
      const auto back = std::lower_bound(directed.begin(), directed.end(), Directed{e.y, e.x, 0, 0});
      if (back == directed.end() || back->x != e.y || back->y != e.x) continue;  // a boundary edge
      const std::vector<std::uint32_t> between = inside_segment(e.x, e.y, plane, verts, index, used);
      if (between.empty()) continue;
      split_triangle(tris, e.t, e.k, between);
      const std::vector<std::uint32_t> reversed(between.rbegin(), between.rend());
      split_triangle(tris, back->t, back->k, reversed);
      inserted += between.size();
      changed = true;
      break;  // the edge list is stale now
    }
  }
  return inserted;
}

}  // namespace ember::core
