// Step 1 of the mesh stage: one id per distinct exact point.
//
// Equal exact points round to equal doubles, so sorting the corners by their
// rounded position brings every class of equal points into one run; distinct
// points that happen to round alike are then told apart exactly (same_point).
// Most corners are grid points (input vertices) stored as the meeting point of
// three planes; as_grid_point recognizes them exactly, so they are rounded and
// compared as integers and stored with w = 1, which keeps the later predicates
// on the filter-or-integer fast paths.
// Ids are numbered by first appearance in output order, so they do not depend
// on the sort or on scheduling.
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_sort.h>

#include <tuple>

#include "core/mesh/mesh_output.hpp"
#include "ember/geometry/exact_order.hpp"

namespace ember::core {

namespace {

struct CornerKey {
  double x, y, z;
  std::uint32_t corner;
  bool grid;  ///< the corner is a grid point (then grid_of[corner] holds it)
  friend bool operator<(const CornerKey& a, const CornerKey& b) {
    return std::tie(a.x, a.y, a.z, a.corner) < std::tie(b.x, b.y, b.z, b.corner);
  }
  bool same_position(const CornerKey& o) const { return x == o.x && y == o.y && z == o.z; }
};

/// The exact corner; only asked for corners that are not grid points, so
/// never for an unbuilt triangle's (OutputPolygon::corners).
const Point& corner_point(std::span<const OutputPolygon> polys, const Cycles& offsets_only,
                          const std::vector<std::uint32_t>& poly_of, std::uint32_t corner) {
  const std::uint32_t p = poly_of[corner];
  return polys[p].vertices[corner - offsets_only.offsets[p]];
}

}  // namespace

OutputVertices exact_weld(std::span<const OutputPolygon> polys, const Quantizer& q) {
  OutputVertices out;
  Cycles& corners = out.corners;
  corners.offsets.resize(polys.size() + 1, 0);
  for (std::size_t i = 0; i < polys.size(); ++i)
    corners.offsets[i + 1] = corners.offsets[i] + static_cast<std::uint32_t>(corner_count(polys[i]));
  const std::size_t n = corners.offsets.back();
  std::vector<std::uint32_t> poly_of(n);
  std::vector<CornerKey> keys(n);
  std::vector<IntPoint> grid_of(n);
  std::vector<char> is_grid(n, 0);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, polys.size(), 256), [&](const auto& r) {
    for (std::size_t i = r.begin(); i != r.end(); ++i)
      for (std::uint32_t c = corners.offsets[i]; c < corners.offsets[i + 1]; ++c) {
        poly_of[c] = static_cast<std::uint32_t>(i);
        const OutputPolygon& p = polys[i];
        const std::uint32_t k = c - corners.offsets[i];
        // An unbuilt triangle's corners are grid points already.
        const std::optional<IntPoint> g = unbuilt(p) ? (*p.corners)[k] : as_grid_point(p.vertices[k]);
        if (g) grid_of[c] = *g, is_grid[c] = 1;
        const Vec3d x = g ? q.dequantize(*g) : q.dequantize(p.vertices[k]);
        keys[c] = {x.x + 0.0, x.y + 0.0, x.z + 0.0, c, g.has_value()};  // -0.0 -> +0.0: equal points, equal keys
      }
  });
  tbb::parallel_sort(keys.begin(), keys.end());

  // Representative (first corner in output order) of each corner's class.
  std::vector<std::uint32_t> rep(n);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, 4096), [&](const auto& r) {
    std::size_t i = r.begin();
    while (i > 0 && i < n && keys[i].same_position(keys[i - 1])) ++i;  // runs belong to the block they start in
    std::vector<std::uint32_t> heads;  // class representatives within the current run
    while (i < r.end() && i < n) {
      std::size_t j = i;
      while (j < n && keys[j].same_position(keys[i])) ++j;
      heads.clear();
      for (std::size_t k = i; k < j; ++k) {
        const std::uint32_t c = keys[k].corner;
        const bool grid = keys[k].grid;
        // Grid-ness belongs to the exact point: a grid corner equals only grid corners.
        auto same = [&](std::uint32_t h) {
          if (grid) return is_grid[h] && grid_of[h] == grid_of[c];
          return !is_grid[h] && same_point(corner_point(polys, corners, poly_of, h),
                                           corner_point(polys, corners, poly_of, c));
        };
        std::uint32_t found = c;
        for (const std::uint32_t h : heads)
          if (same(h)) {
            found = h;
            break;
          }
        if (found == keys[k].corner) heads.push_back(found);
        rep[c] = found;  // keys are sorted by corner within a run: the head is the smallest
      }
      i = j;
    }
  });

  // Number classes by their representative's position in output order: a
  // scan over the head flags, then every corner in parallel.
  std::vector<std::uint32_t> class_of_head(n);
  std::uint32_t classes = 0;
  for (std::size_t c = 0; c < n; ++c) {
    class_of_head[c] = classes;
    classes += rep[c] == c;
  }
  out.exact.resize(classes);
  corners.ids.resize(n);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, 4096), [&](const auto& r) {
    for (std::size_t c = r.begin(); c != r.end(); ++c) {
      const std::uint32_t id = class_of_head[rep[c]];
      corners.ids[c] = id;
      if (rep[c] == c)
        out.exact[id] = is_grid[c] ? to_point(grid_of[c])
                                   : corner_point(polys, corners, poly_of, static_cast<std::uint32_t>(c));
    }
  });
  // Each class's rounded position is its representative's key: rounded once.
  out.rounded.resize(out.exact.size());
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, 4096), [&](const auto& r) {
    for (std::size_t k = r.begin(); k != r.end(); ++k) {
      const std::uint32_t c = keys[k].corner;
      if (rep[c] == c) out.rounded[corners.ids[c]] = {keys[k].x, keys[k].y, keys[k].z};
    }
  });
  return out;
}

}  // namespace ember::core
