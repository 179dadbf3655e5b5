// Winding numbers across shared input edges on the solid path (solid_handover.hpp).
#include "core/solid_handover.hpp"

#include <algorithm>

#include "core/edge_windings.hpp"

namespace ember::core {

std::size_t SolidHandover::hash(const IntPoint& a, const IntPoint& b) {
  std::uint64_t h = 0;
  for (const std::int64_t v : {a.x, a.y, a.z, b.x, b.y, b.z}) h = (h ^ static_cast<std::uint64_t>(v)) * 0x9e3779b97f4a7c15ULL;
  return static_cast<std::size_t>(h ^ (h >> 29));
}

std::uint32_t& SolidHandover::slot(const IntPoint& a, const IntPoint& b) {
  return slots_[hash(a, b) & (slots_.size() - 1)];
}

void SolidHandover::clear() {
  entries_.clear();
  windings_.clear();
  std::fill(slots_.begin(), slots_.end(), UINT32_MAX);
}

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
    for (std::uint32_t x = slot(b, a); x != UINT32_MAX; x = entries_[x].next) {
      const Entry& e = entries_[x];
      if (e.tri != neighbours_[k] || !(e.a == b) || !(e.b == a)) continue;
      if (!share_a_stretch(a, b, from, to, e.from, e.to)) continue;
      const auto at = windings_.begin() + static_cast<std::ptrdiff_t>(2 * operands_ * e.winding);
      front.assign(at, at + static_cast<std::ptrdiff_t>(operands_));
      back.assign(at + static_cast<std::ptrdiff_t>(operands_), at + static_cast<std::ptrdiff_t>(2 * operands_));
      return true;
    }
  }
  return false;
}

void SolidHandover::record(const Polygon& f, const Wnv& front, const Wnv& back) {
  const std::size_t n = f.vertices.size();
  const auto winding = static_cast<std::uint32_t>(windings_.size() / (2 * operands_));
  bool stored = false;
  for (std::size_t i = 0; i < n; ++i) {
    const int k = input_edge_of(f.edges[i]);
    if (k < 0) continue;
    const IntPoint &a = c_[k], &b = c_[(k + 1) % 3];
    std::uint32_t& head = slot(a, b);
    entries_.push_back({f.vertices[i], f.vertices[(i + 1) % n], a, b, id_, winding, head});
    head = static_cast<std::uint32_t>(entries_.size() - 1);
    stored = true;
  }
  if (!stored) return;
  windings_.insert(windings_.end(), front.begin(), front.end());
  windings_.insert(windings_.end(), back.begin(), back.end());
}

}  // namespace ember::core
