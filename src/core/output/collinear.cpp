// Step 3b of the mesh stage: remove boundary vertices that only the
// subdivision or the local BSPs created.
//
// A vertex v whose only boundary edges are a->v->b in one region and b->v->a
// in another region of a non-parallel plane lies on the two planes' common
// line, between a and b: it joins collinear edges between the same two
// regions and is not a corner of either. Removing it on both sides keeps the
// two loops matched edge for edge (a->b against b->a). The test reads only
// ids and the regions' planes: no geometry is computed.
#include "core/output/collinear.hpp"

#include <algorithm>

#include "core/output/regions.hpp"

namespace ember::core {

namespace {

/// Incident alive edges per vertex (CSR), kept up to date while splicing.
struct Incidence {
  std::vector<std::uint32_t> begin;
  std::vector<std::uint32_t> edges;
  Incidence(const std::vector<BoundaryEdge>& all, std::size_t vertex_count, bool outgoing)
      : begin(vertex_count + 1, 0) {
    for (const BoundaryEdge& e : all)
      if (e.alive) ++begin[(outgoing ? e.from : e.to) + 1];
    for (std::size_t v = 0; v < vertex_count; ++v) begin[v + 1] += begin[v];
    edges.resize(begin.back());
    std::vector<std::uint32_t> fill(begin.begin(), begin.end() - 1);
    for (std::uint32_t i = 0; i < all.size(); ++i)
      if (all[i].alive) edges[fill[outgoing ? all[i].from : all[i].to]++] = i;
  }
  std::size_t count(std::uint32_t v) const { return begin[v + 1] - begin[v]; }
  std::uint32_t at(std::uint32_t v, std::size_t k) const { return edges[begin[v] + k]; }
  void replace(std::uint32_t v, std::uint32_t old_edge, std::uint32_t new_edge) {
    for (std::uint32_t k = begin[v]; k < begin[v + 1]; ++k)
      if (edges[k] == old_edge) edges[k] = new_edge;
  }
};

}  // namespace

std::vector<Removal> remove_collinear_vertices(Regions& regions, std::size_t vertex_count,
                                               const std::vector<char>& pinned) {
  std::vector<BoundaryEdge>& e = regions.edges;
  Incidence out(e, vertex_count, true), in(e, vertex_count, false);
  std::vector<Removal> removed;
  for (std::uint32_t v = 0; v < vertex_count; ++v) {
    if (out.count(v) != 2 || in.count(v) != 2 || pinned[v]) continue;
    std::uint32_t o1 = out.at(v, 0), o2 = out.at(v, 1), i1 = in.at(v, 0), i2 = in.at(v, 1);
    if (e[i1].region != e[o1].region) std::swap(i1, i2);
    const std::uint32_t r1 = e[o1].region, r2 = e[o2].region;
    if (r1 == r2 || e[i1].region != r1 || e[i2].region != r2) continue;
    if (e[i1].next != o1 || e[i2].next != o2) continue;
    const std::uint32_t a = e[i1].from, b = e[o1].to;
    if (a == b || e[i2].from != b || e[o2].to != a) continue;
    if (parallel(regions.regions[r1].plane, regions.regions[r2].plane)) continue;
    // a->v->b becomes a->b in r1, b->v->a becomes b->a in r2.
    e[i1].to = b;
    e[i1].next = e[o1].next;
    e[o1].alive = false;
    e[i2].to = a;
    e[i2].next = e[o2].next;
    e[o2].alive = false;
    in.replace(b, o1, i1);
    in.replace(a, o2, i2);
    removed.push_back({v, i1, o1, i2, o2});
  }
  return removed;
}

std::vector<std::uint32_t> restore_vertices(Regions& regions, const std::vector<Removal>& removals,
                                            const std::vector<char>& failed, std::vector<char>& undone) {
  std::vector<BoundaryEdge>& e = regions.edges;
  // A removal must be undone if it touches a failed region, or if it changed
  // an edge that an undone earlier removal changed (it saw that state).
  std::vector<char> undo(removals.size(), 0), dirty(e.size(), 0);
  for (std::size_t k = 0; k < removals.size(); ++k) {
    const Removal& r = removals[k];
    const std::uint32_t rec[4] = {r.in_1, r.out_1, r.in_2, r.out_2};
    if (undone[k]) {  // put back by an earlier call: its edges are in their old state
      for (const std::uint32_t x : rec) dirty[x] = 1;
      continue;
    }
    bool must = failed[e[r.in_1].region] || failed[e[r.in_2].region];
    for (const std::uint32_t x : rec) must = must || dirty[x];
    if (!must) continue;
    undo[k] = 1;
    for (const std::uint32_t x : rec) dirty[x] = 1;
  }
  std::vector<std::uint32_t> changed;
  for (std::size_t k = removals.size(); k-- > 0;) {
    if (!undo[k]) continue;
    undone[k] = 1;
    const Removal& r = removals[k];
    // Splice v back: in -> v -> (what out used to lead to), out alive again.
    e[r.in_1].to = r.v;
    e[r.in_1].next = r.out_1;
    e[r.out_1].alive = true;
    e[r.in_2].to = r.v;
    e[r.in_2].next = r.out_2;
    e[r.out_2].alive = true;
    for (const std::uint32_t reg : {e[r.in_1].region, e[r.in_2].region})
      if (!failed[reg]) changed.push_back(reg);
  }
  std::sort(changed.begin(), changed.end());
  changed.erase(std::unique(changed.begin(), changed.end()), changed.end());
  return changed;
}

}  // namespace ember::core
