// Classified pieces' edges on input edges (piece_edge_table.hpp).
#include "core/route/shared/piece_edge_table.hpp"

#include <algorithm>
#include <bit>
#include <utility>

namespace ember::core {

PieceEdgeTable::PieceEdgeTable(std::size_t operands, std::size_t expected_edges)
    : operands_(operands), slots_(std::bit_ceil(std::max<std::size_t>(64, 2 * expected_edges))) {
  entries_.reserve(expected_edges);
}

void PieceEdgeTable::clear() {
  entries_.clear();
  windings_.clear();
  pieces_ = 0;
  pending_ = false;
  used_ = 0;
  if (++generation_ == 0) {  // wrapped: every slot's stamp could look current
    std::fill(slots_.begin(), slots_.end(), Slot{});
    generation_ = 1;
  }
}

std::size_t PieceEdgeTable::hash(const Key& k) {
  // The table takes the low bits: finish with a multiply-xorshift so that
  // they depend on every coordinate (grid points are highly structured, and
  // linear probing suffers from clustered low bits).
  std::uint64_t h = 0x9E3779B97F4A7C15ull;
  for (const std::int64_t v : {k.a.x, k.a.y, k.a.z, k.b.x, k.b.y, k.b.z})
    h = (h ^ static_cast<std::uint64_t>(v)) * 0xFF51AFD7ED558CCDull;
  h ^= h >> 32;
  h *= 0xC4CEB9FE1A85EC53ull;
  return static_cast<std::size_t>(h ^ (h >> 29));
}

std::uint32_t PieceEdgeTable::first(const IntPoint& a, const IntPoint& b) const {
  const Key k{a, b};
  const std::size_t mask = slots_.size() - 1;
  for (std::size_t i = hash(k) & mask;; i = (i + 1) & mask) {
    const Slot& s = slots_[i];
    if (s.generation != generation_) return UINT32_MAX;
    if (s.key == k) return s.head;
  }
}

std::uint32_t& PieceEdgeTable::head_slot(const Key& k) {
  if (2 * (used_ + 1) > slots_.size()) {  // keep at most half full: short probe runs
    std::vector<Slot> old = std::exchange(slots_, std::vector<Slot>(2 * slots_.size()));
    const std::uint32_t current = std::exchange(generation_, 1);
    used_ = 0;
    for (const Slot& s : old)
      if (s.generation == current) head_slot(s.key) = s.head;
  }
  const std::size_t mask = slots_.size() - 1;
  for (std::size_t i = hash(k) & mask;; i = (i + 1) & mask) {
    Slot& s = slots_[i];
    if (s.generation != generation_) {
      s = Slot{k, UINT32_MAX, generation_};
      ++used_;
      return s.head;
    }
    if (s.key == k) return s.head;
  }
}

void PieceEdgeTable::add_edge(const IntPoint& a, const IntPoint& b, const Point& from, const Point& to,
                              std::uint32_t source) {
  std::uint32_t& head = head_slot(Key{a, b});
  entries_.push_back({from, to, source, pieces_, head});
  head = static_cast<std::uint32_t>(entries_.size() - 1);
  pending_ = true;
}

bool PieceEdgeTable::store(const Wnv& front, const Wnv& back) {
  if (!std::exchange(pending_, false)) return false;
  windings_.insert(windings_.end(), front.begin(), front.end());
  windings_.insert(windings_.end(), back.begin(), back.end());
  ++pieces_;
  return true;
}

void PieceEdgeTable::windings(std::uint32_t w, Wnv& front, Wnv& back) const {
  const auto at = windings_.begin() + static_cast<std::ptrdiff_t>(2 * operands_ * w);
  const auto n = static_cast<std::ptrdiff_t>(operands_);
  front.assign(at, at + n);
  back.assign(at + n, at + 2 * n);
}

}  // namespace ember::core
