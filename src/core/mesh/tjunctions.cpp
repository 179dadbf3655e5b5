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
#include "ember/geometry/exact_order.hpp"

namespace ember::core {

namespace {

/// A set of vertices bucketed in a uniform grid over their rounded positions
/// (cells about one mean edge long, found through a hash table). Positions
/// are copied so that a query touches only the set's own memory.
class VertexIndex {
 public:
  VertexIndex(const std::vector<Vec3d>& all, std::vector<std::uint32_t> members, double mean_edge)
      : ids_(std::move(members)) {
    if (ids_.empty()) return;
    pos_.resize(ids_.size());
    for (std::size_t i = 0; i < ids_.size(); ++i) pos_[i] = all[ids_[i]];
    lo_ = hi_ = pos_[0];
    for (const Vec3d& p : pos_) {
      lo_ = {std::min(lo_.x, p.x), std::min(lo_.y, p.y), std::min(lo_.z, p.z)};
      hi_ = {std::max(hi_.x, p.x), std::max(hi_.y, p.y), std::max(hi_.z, p.z)};
    }
    const double extent = std::max({hi_.x - lo_.x, hi_.y - lo_.y, hi_.z - lo_.z});
    cell_ = std::max(mean_edge, extent * 0x1p-20);
    if (!(cell_ > 0) || !std::isfinite(cell_)) cell_ = 1;
    const auto n = static_cast<std::uint32_t>(pos_.size());
    cells_.resize(n);
    for (std::uint32_t i = 0; i < n; ++i) cells_[i] = {key(cell_of(pos_[i])), i};
    tbb::parallel_sort(cells_.begin(), cells_.end());
    // Open-addressing table: occupied cell key -> its run in cells_.
    std::size_t runs = 0;
    for (std::size_t i = 0; i < n; ++i) runs += i == 0 || cells_[i].first != cells_[i - 1].first;
    std::size_t size = 16;
    while (size < 2 * runs) size *= 2;
    slots_.assign(size, Slot{});
    for (std::uint32_t i = 0; i < n;) {
      std::uint32_t j = i;
      while (j < n && cells_[j].first == cells_[i].first) ++j;
      std::size_t h = hash(cells_[i].first) & (size - 1);
      while (slots_[h].end != 0) h = (h + 1) & (size - 1);
      slots_[h] = {cells_[i].first, i, j};
      i = j;
    }
  }

  /// Calls f(v) for every member whose rounded position lies in the box of
  /// the rounded end points ra, rb and near the segment between them: a point
  /// exactly between a and b rounds into that box (rounding is monotone) and
  /// within a few ulp of the segment through ra and rb. Long edges are cut
  /// into pieces about one cell long, each covering its stretch of the segment
  /// padded by 2^-40 of the largest coordinate (far more than those ulp), so
  /// a long edge visits the cells along it rather than its whole box. A
  /// member near two pieces may be reported twice.
  template <typename F>
  void for_each_near_segment(const Vec3d& ra, const Vec3d& rb, F&& f) const {
    const Vec3d lo{std::min(ra.x, rb.x), std::min(ra.y, rb.y), std::min(ra.z, rb.z)};
    const Vec3d hi{std::max(ra.x, rb.x), std::max(ra.y, rb.y), std::max(ra.z, rb.z)};
    const double span = std::max({hi.x - lo.x, hi.y - lo.y, hi.z - lo.z});
    const double pieces = std::min(std::ceil(span / cell_), 65536.0);
    if (!(pieces > 2)) return for_each_in_box(lo, hi, f);
    const double pad = 0x1p-40 * std::max({std::fabs(lo.x), std::fabs(lo.y), std::fabs(lo.z), std::fabs(hi.x),
                                           std::fabs(hi.y), std::fabs(hi.z)});
    const auto n = static_cast<int>(pieces);
    auto at = [&](int i) {
      const double t = static_cast<double>(i) / n;
      return Vec3d{ra.x + (rb.x - ra.x) * t, ra.y + (rb.y - ra.y) * t, ra.z + (rb.z - ra.z) * t};
    };
    Vec3d p0 = ra;
    for (int i = 1; i <= n; ++i) {
      const Vec3d p1 = i == n ? rb : at(i);
      const Vec3d l{std::max(lo.x, std::min(p0.x, p1.x) - pad), std::max(lo.y, std::min(p0.y, p1.y) - pad),
                    std::max(lo.z, std::min(p0.z, p1.z) - pad)};
      const Vec3d h{std::min(hi.x, std::max(p0.x, p1.x) + pad), std::min(hi.y, std::max(p0.y, p1.y) + pad),
                    std::min(hi.z, std::max(p0.z, p1.z) + pad)};
      for_each_in_box(l, h, f);
      p0 = p1;
    }
  }

  /// Calls f(v) for every member whose rounded position lies in [lo, hi].
  template <typename F>
  void for_each_in_box(const Vec3d& lo, const Vec3d& hi, F&& f) const {
    if (pos_.empty() || hi.x < lo_.x || hi.y < lo_.y || hi.z < lo_.z || lo.x > hi_.x || lo.y > hi_.y ||
        lo.z > hi_.z)
      return;
    const std::array<std::int64_t, 3> c0 = cell_of(lo), c1 = cell_of(hi);
    auto inside = [&](std::uint32_t i) {
      const Vec3d& p = pos_[i];
      return p.x >= lo.x && p.x <= hi.x && p.y >= lo.y && p.y <= hi.y && p.z >= lo.z && p.z <= hi.z;
    };
    for (std::int64_t x = c0[0]; x <= c1[0]; ++x)
      for (std::int64_t y = c0[1]; y <= c1[1]; ++y)
        for (std::int64_t z = c0[2]; z <= c1[2]; ++z) {
          const Slot& slot = find(key({x, y, z}));
          for (std::uint32_t i = slot.begin; i < slot.end; ++i)
            if (inside(cells_[i].second)) f(ids_[cells_[i].second]);
        }
  }

 private:
  static double coord(const Vec3d& p, int a) { return a == 0 ? p.x : (a == 1 ? p.y : p.z); }
  /// Monotone in each coordinate (floating subtraction and division by a
  /// positive constant are monotone), so a box's cells bracket its points'.
  std::array<std::int64_t, 3> cell_of(const Vec3d& p) const {
    auto c = [&](double x, double l) {
      return static_cast<std::int64_t>(std::clamp(std::floor((x - l) / cell_), 0.0, double{(1 << 20) - 1}));
    };
    return {c(p.x, lo_.x), c(p.y, lo_.y), c(p.z, lo_.z)};
  }
  static std::uint64_t key(const std::array<std::int64_t, 3>& c) {
    return (static_cast<std::uint64_t>(c[0]) << 42) | (static_cast<std::uint64_t>(c[1]) << 21) |
           static_cast<std::uint64_t>(c[2]);
  }

  std::vector<std::uint32_t> ids_;  ///< member i is output vertex ids_[i]
  std::vector<Vec3d> pos_;
  Vec3d lo_{}, hi_{};
  double cell_ = 1;
  std::vector<std::pair<std::uint64_t, std::uint32_t>> cells_;  ///< (cell key, member), sorted
  struct Slot {
    std::uint64_t key = 0;
    std::uint32_t begin = 0, end = 0;  ///< run in cells_; end == 0: empty slot
  };
  std::vector<Slot> slots_;
  static std::uint64_t hash(std::uint64_t k) { return (k ^ (k >> 29)) * 0x9E3779B97F4A7C15ull >> 20; }
  const Slot& find(std::uint64_t k) const {
    static constexpr Slot kEmpty{};
    for (std::size_t h = hash(k) & (slots_.size() - 1);; h = (h + 1) & (slots_.size() - 1)) {
      if (slots_[h].end == 0) return kEmpty;
      if (slots_[h].key == k) return slots_[h];
    }
  }
};

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

/// Vertices strictly inside edge k of polygon p, ordered from its start.
void edge_interior_vertices(const Polygon& poly, std::span<const std::uint32_t> ids, std::size_t k,
                            const OutputVertices& verts, const VertexIndex& index, std::vector<std::uint32_t>& found) {
  const std::size_t n = ids.size();
  const std::uint32_t a = ids[k], b = ids[(k + 1) % n];
  const Vec3d &ra = verts.rounded[a], &rb = verts.rounded[b];
  const Plane& edge = poly.edges[k];
  const Plane& before = poly.edges[(k + n - 1) % n];  // crosses the edge's line at a
  const Plane& after = poly.edges[(k + 1) % n];       // crosses it at b
  found.clear();
  index.for_each_near_segment(ra, rb, [&](std::uint32_t v) {
    if (v == a || v == b) return;
    const Point& x = verts.exact[v];
    if (classify(x, poly.support) != 0 || classify(x, edge) != 0) return;
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

Cycles insert_tjunction_vertices(std::span<const OutputPolygon> polys, const OutputVertices& verts,
                                 std::size_t& inserted) {
  std::vector<std::uint32_t> everyone(verts.exact.size());
  for (std::uint32_t v = 0; v < everyone.size(); ++v) everyone[v] = v;
  const VertexIndex index(verts.rounded, std::move(everyone), mean_edge_length(polys, verts));
  const Cycles& corners = verts.corners;
  const EdgePairs pairs = group_edges_by_pair(corners);
  // Per pair: the vertices inside its segment, ordered from the pair's first
  // corner's start vertex (most pairs have none and allocate nothing).
  const std::size_t runs = pairs.run_begin.size() - 1;
  std::vector<std::vector<std::uint32_t>> inside(runs);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, runs, 256), [&](const auto& r) {
    std::vector<std::uint32_t> found;
    for (std::size_t run = r.begin(); run != r.end(); ++run) {
      const std::uint32_t c = pairs.corner[pairs.run_begin[run]], p = pairs.poly_of[c];
      const auto ids = corners[p];
      if (ids[c - corners.offsets[p]] == ids[(c - corners.offsets[p] + 1) % ids.size()]) continue;
      edge_interior_vertices(polys[p].poly, ids, c - corners.offsets[p], verts, index, found);
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
