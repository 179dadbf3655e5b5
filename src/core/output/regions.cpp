// Step 3 of the mesh stage: merge the pieces of each oriented plane into
// regions and drop the vertices that only the subdivision needed.
//
// After step 2 every piece's edges are split at all vertices on them, so two
// pieces of one plane that touch along a segment carry the same directed
// edges, opposite to each other: such edges are interior and cancel. What
// remains around a group of pieces joined that way is the boundary of the
// merged region (outer loop and holes), with the region on the left.
#include "core/output/regions.hpp"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_sort.h>

#include <algorithm>
#include <numeric>
#include <tuple>

#include "core/support/fill_vector.hpp"
#include "core/output/output_vertices.hpp"
#include "geometry/exact_order.hpp"

namespace ember::core {

namespace {

/// The plane scaled to coprime coefficients: equal for coplanar, equally
/// oriented supports of different input triangles (an exact coplanarity id).
struct PlaneKey {
  std::int64_t a, b, c;
  __int128 d;
  friend bool operator<(const PlaneKey& x, const PlaneKey& y) {
    return std::tie(x.a, x.b, x.c, x.d) < std::tie(y.a, y.b, y.c, y.d);
  }
  friend bool operator==(const PlaneKey& x, const PlaneKey& y) {
    return x.a == y.a && x.b == y.b && x.c == y.c && x.d == y.d;
  }
};

PlaneKey canonical(const Plane& p, bool flip) {
  // |a|, |b|, |c| <= 2^52 and |d| < 2^79: they fit int64 / __int128. The
  // normal's gcd is a 64-bit one, and gcd(g, d) = gcd(g, d mod g) needs a
  // single 128-bit remainder.
  const std::int64_t a = static_cast<std::int64_t>(p.a.raw()), b = static_cast<std::int64_t>(p.b.raw()),
                     c = static_cast<std::int64_t>(p.c.raw());
  const __int128 d = p.d.raw();
  std::uint64_t g =
      std::gcd(std::gcd(std::uint64_t(a < 0 ? -a : a), std::uint64_t(b < 0 ? -b : b)), std::uint64_t(c < 0 ? -c : c));
  if (g > 1) {
    const unsigned __int128 ud = static_cast<unsigned __int128>(d < 0 ? -d : d);
    g = std::gcd(g, static_cast<std::uint64_t>(ud % g));
  }
  if (g == 0) g = 1;  // not a plane; keeps the key well defined
  const std::int64_t s = flip ? -1 : 1, gi = static_cast<std::int64_t>(g);
  return {a / gi * s, b / gi * s, c / gi * s, d / gi * s};
}

struct UnionFind {
  std::vector<std::uint32_t> parent;
  explicit UnionFind(std::size_t n) : parent(n) { std::iota(parent.begin(), parent.end(), 0u); }
  std::uint32_t find(std::uint32_t x) {
    while (parent[x] != x) x = parent[x] = parent[parent[x]];
    return x;
  }
  void join(std::uint32_t x, std::uint32_t y) {
    x = find(x), y = find(y);
    if (x != y) parent[std::max(x, y)] = std::min(x, y);
  }
};

/// Calls f(a, b) for every edge of poly's cycle `ids` in the orientation it
/// is emitted with (reversed for a flipped piece), without copying the cycle.
template <typename F>
void for_each_oriented_edge(const OutputPolygon& poly, std::span<const std::uint32_t> ids, F&& f) {
  const std::size_t n = ids.size();
  for (std::size_t k = 0; k < n; ++k) {
    if (poly.flip) {
      f(ids[n - 1 - k], ids[(2 * n - 2 - k) % n]);
    } else {
      f(ids[k], ids[(k + 1) % n]);
    }
  }
}

/// At vertex b, entered from a: the candidate edge that comes first when
/// turning clockwise from the ray b->a. Keeps loops that touch at a vertex
/// apart, each with its region on the left.
std::uint32_t first_clockwise(const OutputVertices& verts, const Plane& plane, std::uint32_t a, std::uint32_t b,
                              const std::vector<BoundaryEdge>& edges, const std::vector<std::uint32_t>& cands) {
  const Point &pa = verts.exact[a], &pb = verts.exact[b];
  int axis = 0;
  while (axis < 2 && compare_coord(pa, pb, axis) == 0) ++axis;
  const int a_side = compare_coord(pa, pb, axis);
  auto half = [&](std::uint32_t c) {
    const int o = orient_in_plane(pb, pa, verts.exact[c], plane);
    if (o < 0) return 0;  // right of the ray: clockwise angle in (0, 180)
    if (o > 0) return 2;
    return compare_coord(verts.exact[c], pb, axis) == a_side ? 3 : 1;  // back along the ray: last
  };
  std::uint32_t best = cands[0];
  int best_half = half(edges[best].to);
  for (std::size_t i = 1; i < cands.size(); ++i) {
    const std::uint32_t e = cands[i];
    const int h = half(edges[e].to);
    if (h < best_half) {
      best = e, best_half = h;
    } else if (h == best_half && (h == 0 || h == 2) &&
               orient_in_plane(pb, verts.exact[edges[e].to], verts.exact[edges[best].to], plane) < 0) {
      best = e;  // best lies clockwise of e: e comes first
    }
  }
  return best;
}

/// Links each boundary edge of one region to the next edge of its loop.
void link_loops(const OutputVertices& verts, const Plane& plane, std::vector<BoundaryEdge>& edges, std::size_t first,
                std::size_t last) {
  std::vector<std::uint32_t> order(last - first);
  std::iota(order.begin(), order.end(), static_cast<std::uint32_t>(first));
  std::sort(order.begin(), order.end(),
            [&](std::uint32_t x, std::uint32_t y) { return std::tie(edges[x].from, x) < std::tie(edges[y].from, y); });
  std::vector<std::uint32_t> cands;
  for (std::size_t e = first; e < last; ++e) {
    const std::uint32_t b = edges[e].to;
    auto it = std::lower_bound(order.begin(), order.end(), b,
                               [&](std::uint32_t x, std::uint32_t v) { return edges[x].from < v; });
    cands.clear();
    for (; it != order.end() && edges[*it].from == b; ++it) cands.push_back(*it);
    if (cands.empty()) {  // an open loop (open input): terminate it on itself
      edges[e].next = static_cast<std::uint32_t>(e);
      continue;
    }
    edges[e].next = cands.size() == 1 ? cands[0] : first_clockwise(verts, plane, edges[e].from, b, edges, cands);
  }
}

struct GroupResult {
  std::vector<Region> regions;
  std::vector<std::vector<std::uint32_t>> pieces;  // per region
  std::vector<std::vector<BoundaryEdge>> edges;    // per region, `region` field local
};

/// A plane with a single piece (most of a curved surface): the piece is its
/// region and its oriented loop the one boundary loop. False if an id still
/// repeats or fewer than 3 remain (then the general path sorts it out).
bool single_piece_loop(const OutputPolygon& poly, std::span<const std::uint32_t> ids, std::vector<std::uint32_t>& loop,
                       std::vector<std::uint32_t>& scratch) {
  piece_loop(poly, ids, loop);
  if (loop.size() < 3) return false;
  scratch.assign(loop.begin(), loop.end());
  std::sort(scratch.begin(), scratch.end());
  return std::adjacent_find(scratch.begin(), scratch.end()) == scratch.end();
}

/// Writes a single-piece loop's edges, linked, in the order the general path
/// gives them (by id pair), so both paths produce the same output. `base` is
/// the index of out[0] in the final edge list.
void write_single_loop(std::span<const std::uint32_t> loop, std::uint32_t region, std::uint32_t base, BoundaryEdge* out,
                       std::vector<std::uint32_t>& order, std::vector<std::uint32_t>& slot) {
  const auto n = static_cast<std::uint32_t>(loop.size());
  auto pair_of = [&](std::uint32_t k) {
    const std::uint32_t a = loop[k], b = loop[(k + 1) % n];
    return std::pair{std::min(a, b), std::max(a, b)};
  };
  order.resize(n);
  std::iota(order.begin(), order.end(), 0u);
  // Distinct ids: no id pair repeats, so the order by pair is strict.
  std::sort(order.begin(), order.end(), [&](std::uint32_t x, std::uint32_t y) { return pair_of(x) < pair_of(y); });
  slot.resize(n);  // cycle position -> position in the sorted edge list
  for (std::uint32_t i = 0; i < n; ++i) slot[order[i]] = i;
  for (std::uint32_t i = 0; i < n; ++i) {
    const std::uint32_t k = order[i];
    out[i] = {loop[k], loop[(k + 1) % n], region, base + slot[(k + 1) % n], true};
  }
}

GroupResult build_group(std::span<const OutputPolygon> polys, const Cycles& cycles,
                        std::span<const std::uint32_t> members, const Plane& plane) {
  struct DirEdge {
    std::uint32_t lo, hi;
    bool forward;  // lo -> hi
    std::uint32_t member;
  };
  std::vector<DirEdge> dir;
  std::size_t corners = 0;
  for (const std::uint32_t p : members) corners += cycles[p].size();
  dir.reserve(corners);
  for (std::uint32_t m = 0; m < members.size(); ++m)
    for_each_oriented_edge(polys[members[m]], cycles[members[m]], [&](std::uint32_t a, std::uint32_t b) {
      if (a != b) dir.push_back({std::min(a, b), std::max(a, b), a < b, m});
    });
  std::sort(dir.begin(), dir.end(), [](const DirEdge& x, const DirEdge& y) {
    return std::tie(x.lo, x.hi, x.forward, x.member) < std::tie(y.lo, y.hi, y.forward, y.member);
  });
  UnionFind uf(members.size());
  std::vector<char> interior(dir.size(), 0);
  for (std::size_t i = 0; i < dir.size();) {
    std::size_t j = i;
    while (j < dir.size() && dir[j].lo == dir[i].lo && dir[j].hi == dir[i].hi) ++j;
    if (j - i == 2 && dir[i].forward != dir[i + 1].forward) {
      uf.join(dir[i].member, dir[i + 1].member);
      interior[i] = interior[i + 1] = 1;
    }
    i = j;
  }
  GroupResult out;
  std::vector<std::uint32_t> region_of(members.size(), UINT32_MAX);
  for (std::uint32_t m = 0; m < members.size(); ++m) {
    const std::uint32_t root = uf.find(m);
    if (region_of[root] == UINT32_MAX) {
      region_of[root] = static_cast<std::uint32_t>(out.regions.size());
      out.regions.push_back({plane, UINT32_MAX});
      out.pieces.emplace_back();
      out.edges.emplace_back();
    }
    Region& r = out.regions[region_of[root]];
    out.pieces[region_of[root]].push_back(members[m]);
    r.source = std::min(r.source, polys[members[m]].id);
  }
  for (std::size_t i = 0; i < dir.size(); ++i) {
    if (interior[i]) continue;
    const DirEdge& d = dir[i];
    const std::uint32_t r = region_of[uf.find(d.member)];
    out.edges[r].push_back({d.forward ? d.lo : d.hi, d.forward ? d.hi : d.lo, r, 0, true});
  }
  return out;
}

}  // namespace

PlaneOrientation::PlaneOrientation(const Plane& plane) {
  const int drop = dominant_axis(plane);
  const std::array<int, 2> uv = projected_axes(drop);
  u_ = uv[0];
  v_ = uv[1];
  flip_ = plane.normal(drop).negative();
}

int orient_in_plane(const Point& a, const Point& b, const Point& c, const Plane& plane) {
  return PlaneOrientation(plane)(a, b, c);
}

void piece_loop(const OutputPolygon& poly, std::span<const std::uint32_t> ids, std::vector<std::uint32_t>& loop) {
  loop.clear();
  for (const std::uint32_t v : ids)
    if (loop.empty() || loop.back() != v) loop.push_back(v);
  while (loop.size() > 1 && loop.front() == loop.back()) loop.pop_back();
  if (poly.flip) std::reverse(loop.begin(), loop.end());
}

Regions build_regions(std::span<const OutputPolygon> polys, const Cycles& cycles, const OutputVertices& verts,
                      const std::vector<char>& skip, std::span<const std::uint32_t> source_groups) {
  const auto face_group = [&](std::uint32_t p) { return source_groups.empty() ? 0u : source_groups[polys[p].id]; };
  // Only kept polygons' keys are written and read. (Value-initialized, the
  // 48-byte keys of a large output would take their page faults in one
  // serial pass.)
  FillVector<PlaneKey> keys(polys.size());
  tbb::parallel_for(std::size_t{0}, polys.size(), [&](std::size_t p) {
    if (!skip[p]) keys[p] = canonical(support_of(polys[p]), polys[p].flip);
  });
  std::vector<std::uint32_t> order;
  order.reserve(polys.size());
  for (std::uint32_t p = 0; p < polys.size(); ++p)
    if (!skip[p]) order.push_back(p);
  const auto kept = static_cast<std::uint32_t>(order.size());
  tbb::parallel_sort(order.begin(), order.end(), [&](std::uint32_t x, std::uint32_t y) {
    if (!(keys[x] == keys[y])) return keys[x] < keys[y];
    return face_group(x) != face_group(y) ? face_group(x) < face_group(y) : x < y;
  });
  std::vector<std::size_t> group_begin;
  for (std::size_t i = 0; i < order.size(); ++i)
    if (i == 0 || !(keys[order[i]] == keys[order[i - 1]]) || face_group(order[i]) != face_group(order[i - 1]))
      group_begin.push_back(i);
  group_begin.push_back(order.size());
  const std::size_t groups = group_begin.size() - 1;

  // Pass 1: single-piece groups only count their loop; the others are merged.
  std::vector<GroupResult> results(groups);
  std::vector<char> single(groups, 0);
  std::vector<std::uint32_t> region_count(groups + 1, 0), edge_count(groups + 1, 0);
  auto members_of = [&](std::size_t g) {
    return std::span<const std::uint32_t>(order.data() + group_begin[g], group_begin[g + 1] - group_begin[g]);
  };
  auto plane_of = [&](std::size_t g) {
    const OutputPolygon& first = polys[order[group_begin[g]]];
    return first.flip ? -support_of(first) : support_of(first);
  };
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, groups, 64), [&](const auto& range) {
    std::vector<std::uint32_t> loop, scratch;
    for (std::size_t g = range.begin(); g != range.end(); ++g) {
      const auto members = members_of(g);
      if (members.size() == 1 && single_piece_loop(polys[members[0]], cycles[members[0]], loop, scratch)) {
        single[g] = 1;
        region_count[g] = 1;
        edge_count[g] = static_cast<std::uint32_t>(loop.size());
        continue;
      }
      const Plane plane = plane_of(g);
      results[g] = build_group(polys, cycles, members, plane);
      region_count[g] = static_cast<std::uint32_t>(results[g].regions.size());
      for (auto& e : results[g].edges) {
        link_loops(verts, plane, e, 0, e.size());
        edge_count[g] += static_cast<std::uint32_t>(e.size());
      }
    }
  });
  // Pass 2: every group writes its regions and edges at its prefix offsets.
  std::exclusive_scan(region_count.begin(), region_count.end(), region_count.begin(), 0u);
  std::exclusive_scan(edge_count.begin(), edge_count.end(), edge_count.begin(), 0u);
  Regions out;
  out.regions.resize(region_count[groups]);
  out.edges.resize(edge_count[groups]);
  out.edge_begin.resize(region_count[groups] + 1);
  out.edge_begin.back() = edge_count[groups];
  // A group's pieces are its members, so its regions' piece lists fill
  // piece_ids[group_begin[g] .. group_begin[g+1]).
  out.piece_ids.resize(kept);
  out.piece_begin.resize(region_count[groups] + 1);
  out.piece_begin.back() = kept;
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, groups, 64), [&](const auto& range) {
    std::vector<std::uint32_t> loop, scratch, slot;
    for (std::size_t g = range.begin(); g != range.end(); ++g) {
      std::uint32_t region = region_count[g], base = edge_count[g];
      if (single[g]) {
        const std::uint32_t p = order[group_begin[g]];
        piece_loop(polys[p], cycles[p], loop);  // checked in pass 1
        out.regions[region] = {plane_of(g), polys[p].id};
        out.piece_ids[group_begin[g]] = p;
        out.piece_begin[region] = static_cast<std::uint32_t>(group_begin[g]);
        out.edge_begin[region] = base;
        write_single_loop(loop, region, base, out.edges.data() + base, scratch, slot);
        continue;
      }
      GroupResult& res = results[g];
      auto piece = static_cast<std::uint32_t>(group_begin[g]);
      for (std::size_t r = 0; r < res.regions.size(); ++r, ++region) {
        out.piece_begin[region] = piece;
        for (const std::uint32_t p : res.pieces[r]) out.piece_ids[piece++] = p;
        out.edge_begin[region] = base;
        for (BoundaryEdge e : res.edges[r]) {
          e.region = region;
          e.next += out.edge_begin[region];
          out.edges[base++] = e;
        }
        out.regions[region] = std::move(res.regions[r]);
      }
    }
  });
  return out;
}

}  // namespace ember::core
