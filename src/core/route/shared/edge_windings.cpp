// Winding numbers across shared input edges inside a leaf (see the header for
// why they are exact).
#include "core/route/shared/edge_windings.hpp"

#include <algorithm>
#include <array>
#include <bit>
#include <utility>

#include "geometry/exact_order.hpp"

namespace ember::core {

std::vector<std::uint32_t> edge_neighbour_order(const Soup& soup, std::size_t begin, std::size_t end) {
  const std::size_t n = end - begin;
  // Each polygon's three input edges as (sorted corner pair, polygon); the
  // polygons of one run of equal edges are neighbours.
  struct Use {
    std::array<std::int64_t, 6> edge;
    std::uint32_t poly;
  };
  std::vector<Use> uses(3 * n);
  for (std::size_t i = 0; i < n; ++i) {
    const std::array<IntPoint, 3>& c = *soup[begin + i].corners;
    for (std::size_t k = 0; k < 3; ++k) {
      std::array<std::int64_t, 3> a{c[k].x, c[k].y, c[k].z}, b{c[(k + 1) % 3].x, c[(k + 1) % 3].y, c[(k + 1) % 3].z};
      if (b < a) std::swap(a, b);
      uses[3 * i + k] = {{a[0], a[1], a[2], b[0], b[1], b[2]}, static_cast<std::uint32_t>(i)};
    }
  }
  std::sort(uses.begin(), uses.end(),
            [](const Use& x, const Use& y) { return x.edge != y.edge ? x.edge < y.edge : x.poly < y.poly; });
  std::vector<std::uint32_t> run_begin, runs_of(3 * n);  // per polygon, its edges' runs
  std::vector<std::uint8_t> filled(n, 0);
  for (std::size_t u = 0; u < uses.size(); ++u) {
    if (u == 0 || uses[u].edge != uses[u - 1].edge) run_begin.push_back(static_cast<std::uint32_t>(u));
    const std::uint32_t p = uses[u].poly;
    runs_of[3 * p + filled[p]++] = static_cast<std::uint32_t>(run_begin.size() - 1);
  }
  run_begin.push_back(static_cast<std::uint32_t>(uses.size()));
  std::vector<std::uint32_t> order;
  order.reserve(n);
  std::vector<char> seen(n, 0);
  for (std::size_t start = 0; start < n; ++start) {
    if (seen[start]) continue;
    seen[start] = 1;
    order.push_back(static_cast<std::uint32_t>(start));
    for (std::size_t at = order.size() - 1; at < order.size(); ++at) {  // the queue is order's tail
      const std::uint32_t p = order[at];
      for (std::size_t k = 0; k < 3; ++k)
        for (std::uint32_t u = run_begin[runs_of[3 * p + k]]; u < run_begin[runs_of[3 * p + k] + 1]; ++u)
          if (!seen[uses[u].poly]) {
            seen[uses[u].poly] = 1;
            order.push_back(uses[u].poly);
          }
    }
  }
  for (std::uint32_t& p : order) p += static_cast<std::uint32_t>(begin);
  return order;
}

EdgeWindings::EdgeWindings(const std::vector<char>& closed, const Box& box, std::size_t expected_edges)
    : operands_(closed.size()), closed_(closed), box_(box), table_(closed.size(), expected_edges) {}

void EdgeWindings::begin_polygon(const Soup& soup, const SoupPolygon& t, std::span<const std::uint32_t> related) {
  soup_ = &soup;
  t_ = &t;
  t_index_ = static_cast<std::uint32_t>(&t - soup.data());
  related_ = related;
  const std::array<IntPoint, 3>& c = *t.corners;
  for (int k = 0; k < 3; ++k) {
    edges_[k].plane = edge_plane(c[k], c[(k + 1) % 3], t.poly->support);
    edges_[k].state = kUnknown;
    edges_[k].blockers.clear();
  }
}

int EdgeWindings::input_edge_of(const Plane& edge) const {
  for (int k = 0; k < 3; ++k)
    if (edges_[k].plane == edge) return k;
  return -1;
}

/// Finds the polygons of `related` that contain a stretch of input edge k's
/// line near the edge (both end points on their plane, boxes overlapping).
/// An edge in a face plane of the box is blocked outright: polygons beyond
/// that face can touch it and are not in the leaf.
void EdgeWindings::classify_edge(int k) {
  InputEdge& e = edges_[k];
  const std::array<IntPoint, 3>& c = *t_->corners;
  const IntPoint& a = c[k];
  const IntPoint& b = c[(k + 1) % 3];
  const std::array<std::int64_t, 3> pa{a.x, a.y, a.z}, pb{b.x, b.y, b.z};
  for (int axis = 0; axis < 3; ++axis) {
    if (pa[axis] == pb[axis] && (pa[axis] == box_.lo[axis] || pa[axis] == box_.hi[axis])) {
      e.state = kBlocked;
      return;
    }
  }
  constexpr std::size_t kMaxBlockers = 8;  // more sheets on one line: not worth sorting out
  e.state = kOpen;
  for (const std::uint32_t i : related_) {
    const SoupPolygon& o = (*soup_)[i];
    bool apart = false;
    for (int axis = 0; axis < 3 && !apart; ++axis) {
      const auto lo = static_cast<double>(std::min(pa[axis], pb[axis]));
      const auto hi = static_cast<double>(std::max(pa[axis], pb[axis]));
      apart = o.hi[axis] < lo || o.lo[axis] > hi;  // o's box is conservative
    }
    if (apart || classify(a, o.poly->support) != 0 || classify(b, o.poly->support) != 0) continue;
    if (on_inner_side(o, t_->poly->support, e.plane)) continue;  // t's twin near the edge
    if (e.blockers.size() == kMaxBlockers) {
      e.state = kBlocked;
      return;
    }
    e.blockers.push_back(i);
  }
}

bool EdgeWindings::on_inner_side(const SoupPolygon& o, const Plane& support, const Plane& edge) const {
  if (!coplanar(o.poly->support, support)) return false;
  for (const Point& v : o.poly->vertices)
    if (classify(v, edge) > 0) return false;
  return true;
}

/// Whether entry e (a piece edge on input edge k's line, recorded from the
/// other side) can hand its winding numbers to the current piece's edge
/// from -> to on that line.
bool EdgeWindings::usable(const PieceEdgeTable::Entry& e, int k, const Point& from, const Point& to) const {
  const SoupPolygon& s = (*soup_)[e.source];
  if (s.operand != t_->operand) return false;
  const InputEdge& edge = edges_[k];
  if (edge.state == kBlocked) return false;
  // A coplanar neighbour must face the same way (it then lies across the
  // edge; facing the other way it would fold back over t).
  const Plane& S = t_->poly->support;
  if (coplanar(S, s.poly->support) && !same_orientation(S, s.poly->support)) return false;
  const std::array<IntPoint, 3>& c = *t_->corners;
  const IntPoint& a = c[k];
  const IntPoint& b = c[(k + 1) % 3];
  // Every other polygon on the line must be a twin of t' on its side.
  if (!edge.blockers.empty()) {
    const Plane source_edge = edge_plane(b, a, s.poly->support);
    for (const std::uint32_t x : edge.blockers)
      if (x != e.source && !on_inner_side((*soup_)[x], s.poly->support, source_edge)) return false;
  }
  return share_a_stretch(a, b, from, to, e.from, e.to);
}

bool share_a_stretch(const IntPoint& a, const IntPoint& b, const Point& from, const Point& to, const Point& n_from,
                     const Point& n_to) {
  // Positive overlap along the line: [n_to, n_from] against [from, to] in the
  // direction a -> b, along an axis in which the line's end points differ.
  const std::array<std::int64_t, 3> d{b.x - a.x, b.y - a.y, b.z - a.z};
  int axis = 0;
  while (d[axis] == 0) ++axis;  // a != b
  const int dir = d[axis] > 0 ? 1 : -1;
  const auto before = [&](const Point& p, const Point& q) { return compare_coord(p, q, axis) * dir < 0; };
  return before(n_to, to) && before(from, n_from);
}

bool EdgeWindings::find(const Polygon& f, std::span<const char> need_front, std::span<const char> need_back, Wnv& front,
                        Wnv& back, bool& full) {
  const std::array<IntPoint, 3>& c = *t_->corners;
  const std::size_t n = f.vertices.size();
  for (std::size_t i = 0; i < n; ++i) {
    const int k = input_edge_of(f.edges[i]);
    if (k < 0) continue;
    if (edges_[k].state == kUnknown) classify_edge(k);
    if (edges_[k].state == kBlocked) continue;
    // Recorded from the other side.
    for (std::uint32_t x = table_.first(c[(k + 1) % 3], c[k]); x != UINT32_MAX; x = table_.entry(x).next) {
      const PieceEdgeTable::Entry& e = table_.entry(x);
      const std::size_t at = 2 * operands_ * e.winding;
      const char* valid = valid_.data() + at;
      bool covers = true, all = true;
      for (std::size_t o = 0; o < operands_; ++o) {
        covers &= (!need_front[o] || valid[o]) && (!need_back[o] || valid[operands_ + o]);
        all &= valid[o] && valid[operands_ + o];
      }
      if (!covers || !usable(e, k, f.vertices[i], f.vertices[(i + 1) % n])) continue;
      table_.windings(e.winding, front, back);
      full = all;
      return true;
    }
  }
  return false;
}

void EdgeWindings::record(const Polygon& f, const Wnv& front, const Wnv& back, std::span<const char> valid_front,
                          std::span<const char> valid_back) {
  const std::array<IntPoint, 3>& c = *t_->corners;
  const std::size_t n = f.vertices.size();
  for (std::size_t i = 0; i < n; ++i) {
    const int k = input_edge_of(f.edges[i]);
    if (k >= 0) table_.add_edge(c[k], c[(k + 1) % 3], f.vertices[i], f.vertices[(i + 1) % n], t_index_);
  }
  if (!table_.store(front, back)) return;
  for (const std::span<const char> valid : {valid_front, valid_back})
    for (std::size_t o = 0; o < operands_; ++o) valid_.push_back(valid[o] && closed_[o]);
}

}  // namespace ember::core
