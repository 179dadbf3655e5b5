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
//
// Most corners belong to unbuilt output triangles (whole input triangles),
// whose corners already carry the set-up's welded grid vertex ids: all the
// corners of one input vertex are one item of the sort (keyed by its first
// corner), so the sort sees each such vertex once instead of once per corner
// (about six times). Only the other corners are sorted one by one. The ids
// come out the same either way: an item stands for the smallest corner it
// covers, and a class's id is ordered by its smallest corner.
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_sort.h>

#include <algorithm>
#include <numeric>
#include <optional>
#include <tuple>

#include "core/mesh/mesh_output.hpp"
#include "ember/geometry/exact_order.hpp"

namespace ember::core {

namespace {

/// A sort key: the rounded position of an item and the smallest corner it stands for.
struct ItemKey {
  double x, y, z;
  std::uint32_t corner;
  std::uint32_t item;
  friend bool operator<(const ItemKey& a, const ItemKey& b) {
    return std::tie(a.x, a.y, a.z, a.corner) < std::tie(b.x, b.y, b.z, b.corner);
  }
  bool same_position(const ItemKey& o) const { return x == o.x && y == o.y && z == o.z; }
};

/// What an item is: a grid point (an input vertex, or a built corner that is
/// one), or otherwise built corner k of polygon `poly`.
struct Item {
  IntPoint grid{};
  std::uint32_t poly = 0;
  std::uint32_t k = 0;
  std::uint32_t corner = 0;  ///< the smallest corner the item stands for
  bool is_grid = false;
};

constexpr std::uint32_t kNone = UINT32_MAX;

/// Per polygon, where its corners are; per input vertex id, its first corner.
struct CornerLayout {
  std::vector<std::uint32_t> built_before;  ///< per polygon: built corners of earlier polygons (+ total)
  std::vector<std::uint32_t> first_corner;  ///< per global input vertex id: smallest corner on it, or kNone
};

/// Whether p's corners are folded into their input vertices' items.
bool folded(const OutputPolygon& p, const InputTopology* ids) { return ids && unbuilt(p); }

std::uint32_t input_vertex(const OutputPolygon& p, std::uint32_t k, const InputTopology& ids) {
  return ids.operand_base[p.operand] + ids.by_triangle[p.id][k];
}

CornerLayout lay_out_corners(std::span<const OutputPolygon> polys, const Cycles& corners, const InputTopology* ids) {
  CornerLayout l;
  l.built_before.resize(polys.size() + 1, 0);
  for (std::size_t i = 0; i < polys.size(); ++i)
    l.built_before[i + 1] = l.built_before[i] + (folded(polys[i], ids) ? 0 : static_cast<std::uint32_t>(corner_count(polys[i])));
  if (!ids) return l;
  l.first_corner.assign(ids->operand_base.back(), kNone);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, polys.size(), 1024), [&](const auto& r) {
    for (std::size_t i = r.begin(); i != r.end(); ++i) {
      if (!folded(polys[i], ids)) continue;
      for (std::uint32_t k = 0; k < 3; ++k)
        atomic_min(l.first_corner[input_vertex(polys[i], k, *ids)], corners.offsets[i] + k);
    }
  });
  return l;
}

/// The exact point of a non-grid item.
const Point& item_point(std::span<const OutputPolygon> polys, const Item& it) { return polys[it.poly].vertices[it.k]; }

}  // namespace

OutputVertices exact_weld(std::span<const OutputPolygon> polys, const Quantizer& q, const InputTopology* ids) {
  OutputVertices out;
  Cycles& corners = out.corners;
  corners.offsets.resize(polys.size() + 1, 0);
  for (std::size_t i = 0; i < polys.size(); ++i)
    corners.offsets[i + 1] = corners.offsets[i] + static_cast<std::uint32_t>(corner_count(polys[i]));
  const std::size_t n = corners.offsets.back();
  CornerLayout layout = lay_out_corners(polys, corners, ids);

  // Items: the built corners (in output order), then the input vertices in
  // use, numbered in id order (a scan).
  std::vector<std::uint32_t> item_of_vertex(layout.first_corner.size());
  std::uint32_t items = layout.built_before.back();
  for (std::uint32_t v = 0; v < layout.first_corner.size(); ++v) {
    item_of_vertex[v] = items;
    items += layout.first_corner[v] != kNone;
  }
  std::vector<Item> item(items);
  std::vector<ItemKey> keys(items);
  auto key_of = [&](std::uint32_t i, std::uint32_t corner, const std::optional<IntPoint>& g, const Point* exact) {
    const Vec3d x = g ? q.dequantize(*g) : q.dequantize(*exact);
    keys[i] = {x.x + 0.0, x.y + 0.0, x.z + 0.0, corner, i};  // -0.0 -> +0.0: equal points, equal keys
  };
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, polys.size(), 256), [&](const auto& r) {
    for (std::size_t i = r.begin(); i != r.end(); ++i) {
      const OutputPolygon& p = polys[i];
      if (folded(p, ids)) continue;
      for (std::uint32_t k = 0; k < corner_count(p); ++k) {
        const std::uint32_t at = layout.built_before[i] + k;
        // An unbuilt triangle's corners are grid points already.
        const std::optional<IntPoint> g = unbuilt(p) ? (*p.corners)[k] : as_grid_point(p.vertices[k]);
        item[at] = {g.value_or(IntPoint{}), static_cast<std::uint32_t>(i), k, corners.offsets[i] + k, g.has_value()};
        key_of(at, corners.offsets[i] + k, g, g ? nullptr : &p.vertices[k]);
      }
    }
  });
  // The input vertex items; from here on first_corner[v] holds v's item.
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, layout.first_corner.size(), 4096), [&](const auto& r) {
    for (std::size_t v = r.begin(); v != r.end(); ++v) {
      std::uint32_t& f = layout.first_corner[v];
      if (f == kNone) continue;
      const std::uint32_t c = f, at = item_of_vertex[v];
      const auto poly = static_cast<std::uint32_t>(
          std::upper_bound(corners.offsets.begin(), corners.offsets.end(), c) - corners.offsets.begin() - 1);
      const IntPoint g = (*polys[poly].corners)[c - corners.offsets[poly]];
      item[at] = {g, poly, c - corners.offsets[poly], c, true};
      key_of(at, c, g, nullptr);
      f = at;
    }
  });
  tbb::parallel_sort(keys.begin(), keys.end());

  // Per item, its class's representative: the smallest corner of the class
  // (that of the class's first item in the run).
  std::vector<std::uint32_t> rep(items);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, items, 4096), [&](const auto& r) {
    std::size_t i = r.begin();
    while (i > 0 && i < items && keys[i].same_position(keys[i - 1])) ++i;  // runs belong to the block they start in
    std::vector<std::uint32_t> heads;  // the items heading the classes of the current run
    while (i < r.end() && i < items) {
      std::size_t j = i;
      while (j < items && keys[j].same_position(keys[i])) ++j;
      heads.clear();
      for (std::size_t k = i; k < j; ++k) {
        const Item& it = item[keys[k].item];
        // Grid-ness belongs to the exact point: a grid point equals only grid points.
        auto same = [&](std::uint32_t h) {
          if (it.is_grid) return item[h].is_grid && item[h].grid == it.grid;
          return !item[h].is_grid && same_point(item_point(polys, item[h]), item_point(polys, it));
        };
        std::uint32_t found = keys[k].item;
        for (const std::uint32_t h : heads)
          if (same(h)) {
            found = h;
            break;
          }
        if (found == keys[k].item) heads.push_back(found);
        rep[keys[k].item] = item[found].corner;  // keys are sorted by corner within a run: the head's is the smallest
      }
      i = j;
    }
  });

  // Number classes by their representative's corner (first appearance in
  // output order): flag the heads' corners, then count along the corners.
  std::vector<std::uint32_t> class_at(n + 1, 0);  // per corner: 1 if it heads a class; then its class
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, items, 4096), [&](const auto& r) {
    for (std::size_t k = r.begin(); k != r.end(); ++k)
      if (rep[keys[k].item] == keys[k].corner) class_at[keys[k].corner] = 1;
  });
  std::exclusive_scan(class_at.begin(), class_at.end(), class_at.begin(), 0u);
  const std::uint32_t classes = class_at[n];
  auto class_of = [&](std::uint32_t it) { return class_at[rep[it]]; };
  out.exact.resize(classes);
  out.rounded.resize(classes);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, items, 4096), [&](const auto& r) {
    for (std::size_t k = r.begin(); k != r.end(); ++k) {
      const ItemKey& key = keys[k];
      if (rep[key.item] != key.corner) continue;
      const Item& it = item[key.item];
      const std::uint32_t id = class_at[key.corner];
      out.exact[id] = it.is_grid ? to_point(it.grid) : item_point(polys, it);
      out.rounded[id] = {key.x, key.y, key.z};  // each class is rounded once
    }
  });
  corners.ids.resize(n);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, polys.size(), 256), [&](const auto& r) {
    for (std::size_t i = r.begin(); i != r.end(); ++i) {
      const OutputPolygon& p = polys[i];
      for (std::uint32_t k = 0; k < corner_count(p); ++k) {
        const std::uint32_t it = folded(p, ids) ? layout.first_corner[input_vertex(p, k, *ids)]
                                                : layout.built_before[i] + k;
        corners.ids[corners.offsets[i] + k] = class_of(it);
      }
    }
  });
  return out;
}

}  // namespace ember::core
