// Step 2 of the mesh stage: insert every output vertex that lies in the open
// interior of a polygon edge into that edge.
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

/// Vertices bucketed in a uniform grid over their rounded positions, plus
/// the vertices sorted along each axis for edges that span many cells.
class VertexIndex {
 public:
  explicit VertexIndex(const std::vector<Vec3d>& pos, double mean_edge) : pos_(pos) {
    if (pos.empty()) return;
    lo_ = hi_ = pos[0];
    for (const Vec3d& p : pos) {
      lo_ = {std::min(lo_.x, p.x), std::min(lo_.y, p.y), std::min(lo_.z, p.z)};
      hi_ = {std::max(hi_.x, p.x), std::max(hi_.y, p.y), std::max(hi_.z, p.z)};
    }
    const double extent = std::max({hi_.x - lo_.x, hi_.y - lo_.y, hi_.z - lo_.z});
    cell_ = std::max(mean_edge, extent * 0x1p-20);
    if (!(cell_ > 0) || !std::isfinite(cell_)) cell_ = 1;
    cells_.resize(pos.size());
    for (std::uint32_t v = 0; v < pos.size(); ++v) cells_[v] = {key(cell_of(pos[v])), v};
    tbb::parallel_sort(cells_.begin(), cells_.end());
    for (int a = 0; a < 3; ++a) {
      by_axis_[a].resize(pos.size());
      for (std::uint32_t v = 0; v < pos.size(); ++v) by_axis_[a][v] = v;
      tbb::parallel_sort(by_axis_[a].begin(), by_axis_[a].end(), [&, a](std::uint32_t x, std::uint32_t y) {
        return coord(pos_[x], a) < coord(pos_[y], a) || (coord(pos_[x], a) == coord(pos_[y], a) && x < y);
      });
    }
  }

  /// Calls f(v) for every vertex whose rounded position lies in [lo, hi].
  template <typename F>
  void for_each_in_box(const Vec3d& lo, const Vec3d& hi, F&& f) const {
    if (pos_.empty()) return;
    const std::array<std::int64_t, 3> c0 = cell_of(lo), c1 = cell_of(hi);
    const double cells = double(c1[0] - c0[0] + 1) * double(c1[1] - c0[1] + 1) * double(c1[2] - c0[2] + 1);
    // The thinnest axis slab, for edges that cross many cells.
    int best_axis = 0;
    std::size_t best_first = 0, best_count = pos_.size() + 1;
    for (int a = 0; a < 3; ++a) {
      const auto& order = by_axis_[a];
      const double l = coord(lo, a), h = coord(hi, a);
      const auto first = std::lower_bound(order.begin(), order.end(), l,
                                          [&](std::uint32_t v, double x) { return coord(pos_[v], a) < x; });
      const auto last = std::upper_bound(first, order.end(), h,
                                         [&](double x, std::uint32_t v) { return x < coord(pos_[v], a); });
      if (static_cast<std::size_t>(last - first) < best_count) {
        best_axis = a;
        best_first = static_cast<std::size_t>(first - order.begin());
        best_count = static_cast<std::size_t>(last - first);
      }
    }
    auto inside = [&](std::uint32_t v) {
      const Vec3d& p = pos_[v];
      return p.x >= lo.x && p.x <= hi.x && p.y >= lo.y && p.y <= hi.y && p.z >= lo.z && p.z <= hi.z;
    };
    if (static_cast<double>(best_count) <= cells * 4) {
      for (std::size_t i = best_first; i < best_first + best_count; ++i)
        if (inside(by_axis_[best_axis][i])) f(by_axis_[best_axis][i]);
      return;
    }
    for (std::int64_t x = c0[0]; x <= c1[0]; ++x)
      for (std::int64_t y = c0[1]; y <= c1[1]; ++y)
        for (std::int64_t z = c0[2]; z <= c1[2]; ++z) {
          const std::uint64_t k = key({x, y, z});
          auto it = std::lower_bound(cells_.begin(), cells_.end(), std::pair<std::uint64_t, std::uint32_t>{k, 0});
          for (; it != cells_.end() && it->first == k; ++it)
            if (inside(it->second)) f(it->second);
        }
  }

 private:
  static double coord(const Vec3d& p, int a) { return a == 0 ? p.x : (a == 1 ? p.y : p.z); }
  /// Monotone in each coordinate (floating subtraction and division by a
  /// positive constant are monotone), so a box's cells bracket its points'.
  std::array<std::int64_t, 3> cell_of(const Vec3d& p) const {
    auto c = [&](double x, double l) {
      return static_cast<std::int64_t>(std::min(std::floor((x - l) / cell_), double{(1 << 20) - 1}));
    };
    return {c(p.x, lo_.x), c(p.y, lo_.y), c(p.z, lo_.z)};
  }
  static std::uint64_t key(const std::array<std::int64_t, 3>& c) {
    return (static_cast<std::uint64_t>(c[0]) << 42) | (static_cast<std::uint64_t>(c[1]) << 21) |
           static_cast<std::uint64_t>(c[2]);
  }

  const std::vector<Vec3d>& pos_;
  Vec3d lo_{}, hi_{};
  double cell_ = 1;
  std::vector<std::pair<std::uint64_t, std::uint32_t>> cells_;
  std::array<std::vector<std::uint32_t>, 3> by_axis_;
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
  const Vec3d lo{std::min(ra.x, rb.x), std::min(ra.y, rb.y), std::min(ra.z, rb.z)};
  const Vec3d hi{std::max(ra.x, rb.x), std::max(ra.y, rb.y), std::max(ra.z, rb.z)};
  const Plane& edge = poly.edges[k];
  const Plane& before = poly.edges[(k + n - 1) % n];  // crosses the edge's line at a
  const Plane& after = poly.edges[(k + 1) % n];       // crosses it at b
  found.clear();
  index.for_each_in_box(lo, hi, [&](std::uint32_t v) {
    if (v == a || v == b) return;
    const Point& x = verts.exact[v];
    if (classify(x, poly.support) != 0 || classify(x, edge) != 0) return;
    if (classify(x, before) < 0 && classify(x, after) < 0) found.push_back(v);
  });
  if (found.size() < 2) return;
  // Points on one line are ordered alike by any coordinate in which the end points differ.
  int axis = 0;
  while (axis < 2 && compare_coord(verts.exact[a], verts.exact[b], axis) == 0) ++axis;
  const bool ascending = compare_coord(verts.exact[a], verts.exact[b], axis) < 0;
  std::sort(found.begin(), found.end(), [&](std::uint32_t x, std::uint32_t y) {
    const int c = compare_coord(verts.exact[x], verts.exact[y], axis);
    return ascending ? c < 0 : c > 0;
  });
}

}  // namespace

Cycles insert_tjunction_vertices(std::span<const OutputPolygon> polys, const OutputVertices& verts,
                                 std::size_t& inserted) {
  const VertexIndex index(verts.rounded, mean_edge_length(polys, verts));
  std::vector<std::vector<std::uint32_t>> per_poly(polys.size());
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, polys.size(), 64), [&](const auto& r) {
    std::vector<std::uint32_t> found;
    for (std::size_t p = r.begin(); p != r.end(); ++p) {
      const auto ids = verts.corners[p];
      std::vector<std::uint32_t>& cycle = per_poly[p];
      for (std::size_t k = 0; k < ids.size(); ++k) {
        cycle.push_back(ids[k]);
        edge_interior_vertices(polys[p].poly, ids, k, verts, index, found);
        cycle.insert(cycle.end(), found.begin(), found.end());
      }
    }
  });
  Cycles out;
  out.offsets.resize(polys.size() + 1, 0);
  for (std::size_t p = 0; p < polys.size(); ++p)
    out.offsets[p + 1] = out.offsets[p] + static_cast<std::uint32_t>(per_poly[p].size());
  out.ids.resize(out.offsets.back());
  tbb::parallel_for(std::size_t{0}, polys.size(), [&](std::size_t p) {
    std::copy(per_poly[p].begin(), per_poly[p].end(), out.ids.begin() + out.offsets[p]);
  });
  inserted = out.ids.size() - verts.corners.ids.size();
  return out;
}

}  // namespace ember::core
