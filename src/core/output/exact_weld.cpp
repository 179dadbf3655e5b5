// Step 1 of the mesh stage: one id per distinct exact point.
//
// Equal exact points have equal keys, so sorting the corners by a hash of
// their key brings every class of equal points into one run; distinct points
// whose hashes collide are then told apart exactly. The key is exact for grid
// points: most corners are grid points (input vertices) stored as the meeting
// point of three planes; as_grid_point recognizes them exactly, so they are
// hashed, rounded and compared as integers and stored with w = 1, which keeps
// the later predicates on the filter-or-integer fast paths. Other points are
// keyed by their correctly rounded position (equal points round alike) and
// compared exactly (same_point) within a run.
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
//
// The sort is a radix sort of (32-bit hash, item) pairs (sort_pairs): a
// comparison sort of the positions cost ~17 compare-and-move steps per item.
#include "core/output/exact_weld.hpp"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <bit>
#include <numeric>
#include <optional>

#include "core/support/fill_vector.hpp"
#include "core/output/output_vertices.hpp"
#include "core/support/sort_pairs.hpp"
#include "geometry/exact_order.hpp"

namespace ember::core {

namespace {

/// A 32-bit hash of a key: its three 64-bit words mixed (the key is the
/// grid point for grid items, the rounded position's bits otherwise). Equal
/// keys hash alike; collisions only cost an exact comparison.
std::uint32_t hash_key(std::uint64_t x, std::uint64_t y, std::uint64_t z) {
  std::uint64_t h = x * 0x9E3779B97F4A7C15ull;
  h = (h ^ (h >> 29) ^ y) * 0xBF58476D1CE4E5B9ull;
  h = (h ^ (h >> 32) ^ z) * 0x94D049BB133111EBull;
  return static_cast<std::uint32_t>(h >> 32);
}

/// What an item is: a grid point (an input vertex, or a built corner that is
/// one), or otherwise built corner k of polygon `poly`.
struct Item {
  IntPoint grid{};
  std::uint32_t poly = 0;
  std::uint32_t k = 0;
  std::uint32_t corner = 0;  ///< the smallest corner the item stands for
  bool is_grid = false;
};

/// Per polygon, where its corners are; per input vertex id, its first corner.
struct CornerLayout {
  std::vector<std::uint32_t> built_before;  ///< per polygon: built corners of earlier polygons (+ total)
  /// Per global input vertex id: its smallest corner c and that corner's
  /// polygon p as c << 32 | p (a minimum by corner), or kNoCorner.
  std::vector<std::uint64_t> first_corner;
};

constexpr std::uint64_t kNoCorner = UINT64_MAX;

/// Whether p's corners are folded into their input vertices' items.
bool folded(const OutputPolygon& p, const InputTopology* ids) { return ids && unbuilt(p); }

std::uint32_t input_vertex(const OutputPolygon& p, std::uint32_t k, const InputTopology& ids) {
  return ids.operand_base[p.operand] + ids.by_triangle[p.id][k];
}

CornerLayout lay_out_corners(std::span<const OutputPolygon> polys, const Cycles& corners, const InputTopology* ids) {
  CornerLayout l;
  l.built_before.resize(polys.size() + 1, 0);
  for (std::size_t i = 0; i < polys.size(); ++i)
    l.built_before[i + 1] =
        l.built_before[i] + (folded(polys[i], ids) ? 0 : static_cast<std::uint32_t>(corner_count(polys[i])));
  if (!ids) return l;
  l.first_corner.assign(ids->operand_base.back(), kNoCorner);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, polys.size(), 1024), [&](const auto& r) {
    for (std::size_t i = r.begin(); i != r.end(); ++i) {
      if (!folded(polys[i], ids)) continue;
      for (std::uint32_t k = 0; k < 3; ++k)
        atomic_min(l.first_corner[input_vertex(polys[i], k, *ids)],
                   std::uint64_t{corners.offsets[i] + k} << 32 | static_cast<std::uint32_t>(i));
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
  const CornerLayout layout = lay_out_corners(polys, corners, ids);

  // Items: the built corners (in output order), then the input vertices in
  // use, numbered in id order (a scan).
  std::vector<std::uint32_t> item_of_vertex(layout.first_corner.size());
  std::uint32_t items = layout.built_before.back();
  for (std::uint32_t v = 0; v < layout.first_corner.size(); ++v) {
    item_of_vertex[v] = items;
    items += layout.first_corner[v] != kNoCorner;
  }
  // Every item is written below (built corners, then used input vertices).
  FillVector<Item> item(items);
  FillVector<Vec3d> rounded(items);                                  // per item: its rounded position
  FillVector<std::pair<std::uint32_t, std::uint32_t>> keyed(items);  // (hash of the key, item)
  auto set_key = [&](std::uint32_t i, const std::optional<IntPoint>& g, const Point* exact) {
    const Vec3d x = g ? q.dequantize(*g) : q.dequantize(*exact);
    rounded[i] = {x.x + 0.0, x.y + 0.0, x.z + 0.0};  // -0.0 -> +0.0: equal points, equal keys
    const std::uint32_t h =
        g ? hash_key(static_cast<std::uint64_t>(g->x), static_cast<std::uint64_t>(g->y),
                     static_cast<std::uint64_t>(g->z))
          : hash_key(std::bit_cast<std::uint64_t>(rounded[i].x), std::bit_cast<std::uint64_t>(rounded[i].y),
                     std::bit_cast<std::uint64_t>(rounded[i].z));
    keyed[i] = {h, i};
  };
  // Fine grain: the work is the rounding of built corners (~850 instructions
  // each), and the built polygons come in a cluster (the solid path emits
  // its cut pieces after the whole triangles, which cost nothing here).
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, polys.size(), 16), [&](const auto& r) {
    for (std::size_t i = r.begin(); i != r.end(); ++i) {
      const OutputPolygon& p = polys[i];
      if (folded(p, ids)) continue;
      for (std::uint32_t k = 0; k < corner_count(p); ++k) {
        const std::uint32_t at = layout.built_before[i] + k;
        // An unbuilt triangle's corners are grid points already.
        const std::optional<IntPoint> g = unbuilt(p) ? (*p.corners)[k] : as_grid_point(p.vertices[k]);
        item[at] = {g.value_or(IntPoint{}), static_cast<std::uint32_t>(i), k, corners.offsets[i] + k, g.has_value()};
        set_key(at, g, g ? nullptr : &p.vertices[k]);
      }
    }
  });
  // The input vertex items (grain 512: each rounds a point, and a small
  // Boolean's few thousand must still be shared by two threads).
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, layout.first_corner.size(), 512), [&](const auto& r) {
    for (std::size_t v = r.begin(); v != r.end(); ++v) {
      const std::uint64_t f = layout.first_corner[v];
      if (f == kNoCorner) continue;
      const auto c = static_cast<std::uint32_t>(f >> 32), poly = static_cast<std::uint32_t>(f);
      const IntPoint g = (*polys[poly].corners)[c - corners.offsets[poly]];
      const std::uint32_t at = item_of_vertex[v];
      item[at] = {g, poly, c - corners.offsets[poly], c, true};
      set_key(at, g, nullptr);
    }
  });
  sort_pairs(keyed);  // filled in item order: the radix path

  // Per item, its class's representative: the smallest corner of the class.
  // Grid-ness belongs to the exact point: a grid point equals only grid points.
  auto same = [&](std::uint32_t a, std::uint32_t b) {
    const Item &x = item[a], &y = item[b];
    if (x.is_grid || y.is_grid) return x.is_grid && y.is_grid && x.grid == y.grid;
    const Vec3d &ra = rounded[a], &rb = rounded[b];
    return ra.x == rb.x && ra.y == rb.y && ra.z == rb.z && same_point(item_point(polys, x), item_point(polys, y));
  };
  FillVector<std::uint32_t> rep(items);  // every run writes all of its items
  // Runs of equal hashes are compared exactly (same_point): a few thousand
  // items are work enough to share.
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, items, 512), [&](const auto& r) {
    std::size_t i = r.begin();
    while (i > 0 && i < items && keyed[i].first == keyed[i - 1].first) ++i;  // runs belong to the block they start in
    std::vector<std::uint32_t> head, smallest, class_of;  // per class of the run: an item, its smallest corner
    while (i < r.end() && i < items) {
      std::size_t j = i + 1;
      while (j < items && keyed[j].first == keyed[i].first) ++j;
      if (j == i + 1) {  // most runs: one item
        rep[keyed[i].second] = item[keyed[i].second].corner;
        i = j;
        continue;
      }
      head.clear(), smallest.clear(), class_of.clear();
      for (std::size_t k = i; k < j; ++k) {
        const std::uint32_t it = keyed[k].second;
        std::size_t c = 0;
        while (c < head.size() && !same(head[c], it)) ++c;
        if (c == head.size()) {
          head.push_back(it);
          smallest.push_back(item[it].corner);
        }
        smallest[c] = std::min(smallest[c], item[it].corner);
        class_of.push_back(static_cast<std::uint32_t>(c));
      }
      for (std::size_t k = i; k < j; ++k) rep[keyed[k].second] = smallest[class_of[k - i]];
      i = j;
    }
  });

  // Number classes by their representative's corner (first appearance in
  // output order): flag the heads' corners, then count along the corners.
  // The large buffers below take their page faults in parallel
  // (reserve_touched): value-initialized, they were serial steps of the
  // weld that did not shrink with more threads.
  std::vector<std::uint32_t> class_at;  // per corner: 1 if it heads a class; then its class
  reserve_touched(class_at, n + 1);
  class_at.resize(n + 1, 0);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, items, 4096), [&](const auto& r) {
    for (std::size_t it = r.begin(); it != r.end(); ++it)
      if (rep[it] == item[it].corner) class_at[item[it].corner] = 1;
  });
  std::exclusive_scan(class_at.begin(), class_at.end(), class_at.begin(), 0u);
  const std::uint32_t classes = class_at[n];
  auto class_of = [&](std::uint32_t it) { return class_at[rep[it]]; };
  reserve_touched(out.exact, classes);
  out.exact.resize(classes);
  reserve_touched(out.rounded, classes);
  out.rounded.resize(classes);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, items, 512), [&](const auto& r) {
    for (std::size_t it = r.begin(); it != r.end(); ++it) {
      const Item& x = item[it];
      if (rep[it] != x.corner) continue;
      const std::uint32_t id = class_at[x.corner];
      out.exact[id] = x.is_grid ? to_point(x.grid) : item_point(polys, x);
      out.rounded[id] = rounded[it];  // each class is rounded once
    }
  });
  // From here on item_of_vertex holds each used input vertex's class, so
  // that a folded corner (most corners) costs one lookup.
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, layout.first_corner.size(), 4096), [&](const auto& r) {
    for (std::size_t v = r.begin(); v != r.end(); ++v)
      if (layout.first_corner[v] != kNoCorner) item_of_vertex[v] = class_of(item_of_vertex[v]);
  });
  reserve_touched(corners.ids, n);
  corners.ids.resize(n);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, polys.size(), 1024), [&](const auto& r) {
    for (std::size_t i = r.begin(); i != r.end(); ++i) {
      const OutputPolygon& p = polys[i];
      std::uint32_t* out_ids = corners.ids.data() + corners.offsets[i];
      if (folded(p, ids)) {
        const std::uint32_t base = ids->operand_base[p.operand];
        const std::array<std::uint32_t, 3>& v = ids->by_triangle[p.id];
        for (int k = 0; k < 3; ++k) out_ids[k] = item_of_vertex[base + v[k]];
      } else {
        for (std::uint32_t k = 0; k < corner_count(p); ++k) out_ids[k] = class_of(layout.built_before[i] + k);
      }
    }
  });
  return out;
}

}  // namespace ember::core
