// Winding numbers across shared input edges on the solid path (solid_handover.hpp).
#include "core/route/solid/solid_handover.hpp"

#include <algorithm>

#include "core/route/shared/edge_windings.hpp"
#include "geometry/exact_order.hpp"
#include "geometry/polygon.hpp"

namespace ember::core {

void SolidHandover::clear() { table_.clear(); }

void SolidHandover::begin_triangle(std::uint32_t id, const Polygon& t, std::span<const std::uint32_t> partners,
                                   const GridTriangles& grid) {
  id_ = id;
  t_ = &t;
  c_ = grid.corners[id];
  neighbours_ = grid.neighbors[id];
  partners_ = partners;
  grid_ = &grid;
  blocked_ = {-1, -1, -1};
}

int SolidHandover::input_edge_of(const Plane& e) const {
  for (int k = 0; k < 3; ++k)
    if (t_->edges[k] == e) return k;  // clip keeps the edge planes of t's pieces
  return -1;
}

bool SolidHandover::blocked(int k) {
  if (blocked_[k] >= 0) return blocked_[k] != 0;
  const IntPoint &a = c_[k], &b = c_[(k + 1) % 3];
  // Not manifold, or a partner of t whose plane holds the edge's line.
  bool block = neighbours_[k] == kNoNeighbor;
  for (std::size_t i = 0; i < partners_.size() && !block; ++i) {
    const std::array<IntPoint, 3>& q = grid_->corners[partners_[i]];
    const std::array<std::int64_t, 3> n = grid_normal(q[0], q[1], q[2]);
    block = grid_side(q[0], n, a) == 0 && grid_side(q[0], n, b) == 0;
  }
  blocked_[k] = block ? 1 : 0;
  return block;
}

bool SolidHandover::find(const Polygon& f, Wnv& front, Wnv& back) {
  const std::size_t n = f.vertices.size();
  for (std::size_t i = 0; i < n; ++i) {
    const int k = input_edge_of(f.edges[i]);
    if (k < 0 || blocked(k)) continue;
    const IntPoint &a = c_[k], &b = c_[(k + 1) % 3];
    const Point &from = f.vertices[i], &to = f.vertices[(i + 1) % n];
    for (std::uint32_t x = table_.first(b, a); x != UINT32_MAX; x = table_.entry(x).next) {
      const PieceEdgeTable::Entry& e = table_.entry(x);
      if (e.source != neighbours_[k]) continue;
      if (!share_a_stretch(a, b, from, to, e.from, e.to)) continue;
      table_.windings(e.winding, front, back);
      return true;
    }
  }
  return false;
}

void SolidHandover::record(const Polygon& f, const Wnv& front, const Wnv& back) {
  const std::size_t n = f.vertices.size();
  for (std::size_t i = 0; i < n; ++i) {
    const int k = input_edge_of(f.edges[i]);
    if (k >= 0) table_.add_edge(c_[k], c_[(k + 1) % 3], f.vertices[i], f.vertices[(i + 1) % n], id_);
  }
  table_.store(front, back);
}

void PieceWindings::reset(std::size_t pieces, std::size_t operand_count) {
  operands = operand_count;
  w.resize(2 * operands * pieces);
  known.assign(pieces, 0);
  order.clear();
}

void PieceWindings::store(std::size_t m, const Wnv& front, const Wnv& back) {
  const auto at = w.begin() + static_cast<std::ptrdiff_t>(2 * operands * m);
  std::copy(front.begin(), front.end(), at);
  std::copy(back.begin(), back.end(), at + static_cast<std::ptrdiff_t>(operands));
  known[m] = 1;
  order.push_back(static_cast<std::uint32_t>(m));
}

void PieceWindings::get(std::size_t m, Wnv& front, Wnv& back) const {
  const auto at = w.begin() + static_cast<std::ptrdiff_t>(2 * operands * m);
  front.assign(at, at + static_cast<std::ptrdiff_t>(operands));
  back.assign(at + static_cast<std::ptrdiff_t>(operands), at + static_cast<std::ptrdiff_t>(2 * operands));
}

std::array<std::int64_t, 3> CutHandover::key_of(const Plane& e) {
  std::array<std::int64_t, 3> k{static_cast<std::int64_t>(e.a.raw()), static_cast<std::int64_t>(e.b.raw()),
                                static_cast<std::int64_t>(e.c.raw())};
  const std::int64_t first = k[0] != 0 ? k[0] : (k[1] != 0 ? k[1] : k[2]);
  if (first < 0)
    for (std::int64_t& x : k) x = -x;  // e and -e: one key
  return k;
}

void CutHandover::begin_triangle(const Polygon& t, std::span<const Polygon* const> partner,
                                 std::span<const std::uint32_t> partner_operand) {
  t_ = &t;
  partner_ = partner;
  operand_ = partner_operand;
  lines_.clear();
  for (std::size_t i = 0; i < partner.size(); ++i)
    lines_.push_back({key_of(partner[i]->support), partner[i]->support, i, -1});
  std::sort(lines_.begin(), lines_.end(),
            [](const Line& a, const Line& b) { return a.key != b.key ? a.key < b.key : a.partner < b.partner; });
  // Two partners on one plane both hold its lines: blocked.
  for (std::size_t i = 0; i < lines_.size(); ++i) {
    for (std::size_t j = i + 1; j < lines_.size() && lines_[j].key == lines_[i].key; ++j)
      if (lines_[j].plane == lines_[i].plane || lines_[j].plane == -lines_[i].plane)
        lines_[i].state = lines_[j].state = 1;
  }
}

int CutHandover::line_of(const Plane& e) const {
  const std::array<std::int64_t, 3> k = key_of(e);
  auto it = std::lower_bound(lines_.begin(), lines_.end(), k,
                             [](const Line& l, const std::array<std::int64_t, 3>& key) { return l.key < key; });
  for (; it != lines_.end() && it->key == k; ++it)
    if (it->plane == e || it->plane == -e) return static_cast<int>(it - lines_.begin());
  return -1;
}

void CutHandover::decide(Line& line, const Point& p, const Point& q) const {
  // No other partner's plane holds the line (p and q both on it). U then
  // reaches both sides of t's plane (solid_handover.hpp); checked as well,
  // as a guard on that argument.
  const Polygon& u = *partner_[line.partner];
  bool front = false, back = false;
  for (const Point& v : u.vertices) {
    const int s = classify(v, t_->support);
    front |= s > 0;
    back |= s < 0;
  }
  bool open = front && back;
  for (std::size_t i = 0; i < partner_.size() && open; ++i)
    if (i != line.partner && classify(p, partner_[i]->support) == 0 && classify(q, partner_[i]->support) == 0)
      open = false;
  line.state = open ? 0 : 1;
}

bool CutHandover::derive(const Polygon& f, const Polygon& g, const Wnv& g_front, const Wnv& g_back, Wnv& front,
                         Wnv& back) {
  for (std::size_t i = 0; i < f.edges.size(); ++i) {
    const Plane& e = f.edges[i];
    if (e == t_->edges[0] || e == t_->edges[1] || e == t_->edges[2]) continue;  // an input edge
    const Plane flipped = -e;
    for (std::size_t j = 0; j < g.edges.size(); ++j) {
      if (!(g.edges[j] == flipped)) continue;
      const int line = line_of(e);
      if (line >= 0 && derive(f, i, g, j, line, g_front, g_back, front, back)) return true;
    }
  }
  return false;
}

bool CutHandover::derive(const Polygon& f, std::size_t i, const Polygon& g, std::size_t j, int line_index,
                         const Wnv& g_front, const Wnv& g_back, Wnv& front, Wnv& back) {
  Line& line = lines_[static_cast<std::size_t>(line_index)];
  if (line.state == 1 || !(g.edges[j] == -f.edges[i])) return false;
  // Edges on one line running opposite ways: the stretch both cover, in f's
  // direction, along an axis in which f's edge moves.
  const std::size_t nf = f.vertices.size(), ng = g.vertices.size();
  const Point &from = f.vertices[i], &to = f.vertices[(i + 1) % nf];
  const Point &g_from = g.vertices[j], &g_to = g.vertices[(j + 1) % ng];
  int axis = 0;
  while (axis < 2 && compare_coord(from, to, axis) == 0) ++axis;
  const int dir = compare_coord(to, from, axis);  // f's edge has length: not 0
  const auto before = [&](const Point& a, const Point& b) { return compare_coord(b, a, axis) == dir; };
  if (!before(g_to, to) || !before(from, g_from)) return false;  // no stretch of positive length
  const Point& lo = before(from, g_to) ? g_to : from;
  const Point& hi = before(to, g_from) ? to : g_from;
  if (line.state < 0) decide(line, lo, hi);
  if (line.state != 0) return false;
  const Polygon& u = *partner_[line.partner];
  front = g_front;
  back = g_back;
  if (locate(u, lo) <= 0 && locate(u, hi) <= 0) {
    // g behind U (its edge on U's plane as clipped: the negative side) to f
    // in front: out of U's operand, one less; the other way one more.
    const int step = g.edges[j] == u.support ? -1 : 1;
    front[operand_[line.partner]] += step;
    back[operand_[line.partner]] += step;
  }
  return true;
}

bool CutHandover::spread(std::span<const Piece> pieces, PieceWindings& pw,
                         const std::function<bool(std::size_t, Wnv&, Wnv&)>& trace) {
  const std::size_t n = pieces.size();
  if (n <= kFewPieces) return spread_among_few(pieces, pw, trace);
  // The pieces' edges on cut lines, by piece and by line.
  piece_edges_.clear();
  piece_begin_.resize(n + 1);
  for (std::size_t m = 0; m < n; ++m) {
    piece_begin_[m] = static_cast<std::uint32_t>(piece_edges_.size());
    const Polygon& f = pieces[m].poly;
    for (std::size_t i = 0; i < f.edges.size(); ++i)
      if (const int line = line_of(f.edges[i]); line >= 0)
        piece_edges_.push_back(
            {static_cast<std::uint32_t>(line), static_cast<std::uint32_t>(m), static_cast<std::uint32_t>(i)});
  }
  piece_begin_[n] = static_cast<std::uint32_t>(piece_edges_.size());
  line_edges_ = piece_edges_;
  std::sort(line_edges_.begin(), line_edges_.end(),
            [](const CutEdge& a, const CutEdge& b) { return a.line != b.line ? a.line < b.line : a.piece < b.piece; });
  Wnv front, back;
  std::size_t head = 0, first_unknown = 0;
  while (!pw.complete()) {
    if (head == pw.order.size()) {  // nothing known reaches the rest: trace the first of them
      while (pw.known[first_unknown]) ++first_unknown;
      if (!trace(first_unknown, front, back)) return false;
      pw.store(first_unknown, front, back);
      continue;
    }
    const std::uint32_t g = pw.order[head++];
    pw.get(g, g_front_, g_back_);
    for (std::uint32_t k = piece_begin_[g]; k < piece_begin_[g + 1]; ++k) {
      const CutEdge e = piece_edges_[k];
      auto c = std::lower_bound(line_edges_.begin(), line_edges_.end(), e.line,
                                [](const CutEdge& x, std::uint32_t line) { return x.line < line; });
      for (; c != line_edges_.end() && c->line == e.line; ++c)
        if (!pw.known[c->piece] && derive(pieces[c->piece].poly, c->edge, pieces[g].poly, e.edge,
                                          static_cast<int>(e.line), g_front_, g_back_, front, back))
          pw.store(c->piece, front, back);
    }
  }
  return true;
}

bool CutHandover::spread_among_few(std::span<const Piece> pieces, PieceWindings& pw,
                                   const std::function<bool(std::size_t, Wnv&, Wnv&)>& trace) {
  const std::size_t n = pieces.size();
  Wnv front, back;
  while (!pw.complete()) {
    bool spread = false;
    for (std::size_t m = 0; m < n; ++m)
      for (std::size_t g = 0; g < n && !pw.known[m]; ++g) {
        if (!pw.known[g]) continue;
        pw.get(g, g_front_, g_back_);
        if (!derive(pieces[m].poly, pieces[g].poly, g_front_, g_back_, front, back)) continue;
        pw.store(m, front, back);
        spread = true;
      }
    if (spread) continue;
    std::size_t m = 0;  // nothing known reaches the rest: trace the first of them
    while (pw.known[m]) ++m;
    if (!trace(m, front, back)) return false;
    pw.store(m, front, back);
  }
  return true;
}

}  // namespace ember::core
