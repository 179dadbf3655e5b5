#pragma once
// The solid path's polygon-local BSPs (solid_route.hpp, step 2): a touched
// triangle cut by its partners, and the cache of built partner polygons.
#include <algorithm>
#include <array>
#include <cstdint>
#include <deque>
#include <span>
#include <utility>
#include <vector>

#include "core/route/shared/pieces.hpp"
#include "core/model/grid_triangles.hpp"

namespace ember::core {

/// Built polygons of the triangles near the ones being processed, by id:
/// a touched triangle's partners are mostly the previous one's (triangles go
/// in curve order), so each is built about once per thread while the cache
/// stays under kKeep. References stay valid until reset_if_full() empties it.
class PolygonCache {
 public:
  /// Built triangles kept whatever the next triangle needs: about 2.5 MB
  /// per thread.
  static constexpr std::size_t kKeep = 4096;
  explicit PolygonCache(const GridTriangles& grid) : grid_(grid) { slots_.assign(1024, kEmpty); }
  const Polygon& get(std::uint32_t id) {
    std::size_t h = (id * 0x9e3779b1u) & (slots_.size() - 1);
    for (; slots_[h].first != kNone; h = (h + 1) & (slots_.size() - 1))
      if (slots_[h].first == id) return pool_[slots_[h].second];
    if (used_ == pool_.size()) pool_.emplace_back();
    const std::array<IntPoint, 3>& c = grid_.corners[id];
    assign_triangle(c[0], c[1], c[2], pool_[used_]);  // a soup triangle has area
    slots_[h] = {id, static_cast<std::uint32_t>(used_)};
    if (2 * ++used_ > slots_.size()) grow();
    return pool_[used_ - 1];
  }
  const std::array<IntPoint, 3>& corners(std::uint32_t id) const { return grid_.corners[id]; }
  /// How many built triangles the cache holds.
  std::size_t size() const { return used_; }
  /// Forgets everything (buffers are kept) once the cache holds far more
  /// than the next triangle needs (`partners` + itself) and more than
  /// kKeep polygons. Without that floor a triangle with few partners would
  /// empty the cache between two crowded ones, and a pile of small operands
  /// would build its triangles many times over.
  void reset_if_full(std::size_t partners) {
    if (used_ < std::max(kKeep, 256 + 2 * partners)) return;
    std::fill(slots_.begin(), slots_.end(), kEmpty);
    used_ = 0;
  }

 private:
  static constexpr std::uint32_t kNone = UINT32_MAX;
  static constexpr std::pair<std::uint32_t, std::uint32_t> kEmpty{kNone, 0};
  void grow() {
    std::vector<std::pair<std::uint32_t, std::uint32_t>> old(2 * slots_.size(), kEmpty);
    old.swap(slots_);
    for (const auto& e : old) {
      if (e.first == kNone) continue;
      std::size_t h = (e.first * 0x9e3779b1u) & (slots_.size() - 1);
      while (slots_[h].first != kNone) h = (h + 1) & (slots_.size() - 1);
      slots_[h] = e;
    }
  }
  const GridTriangles& grid_;
  std::vector<std::pair<std::uint32_t, std::uint32_t>> slots_;
  std::deque<Polygon> pool_;  ///< stable references
  std::size_t used_ = 0;
};

/// A piece's conservative box (approx_bounds).
struct PieceBox {
  std::array<double, 3> lo, hi;
};

/// Scratch of the polygon-local BSP of one triangle.
struct CutScratch {
  std::vector<PieceBox> boxes;  ///< per piece
  std::span<const std::uint32_t> partners;
  std::vector<Piece> pieces, next;
  std::vector<std::int8_t> other_signs, signs;
  std::vector<Plane> cons;
  Polygon neg, pos;
  /// Per partner (same order): its plane is t's (cut_triangle records it).
  std::vector<char> coplanar;
};

/// t's pieces (Section 4.3 with closed operands and no box): what lower-id
/// coplanar partners cover is cut away and left to them (Fig. 8), then every
/// transverse partner touching t's plane cuts along its plane (C3). Higher-id
/// coplanar partners need no cut: their edges continue into triangles of
/// their closed operand that leave the plane, whose C3 cuts separate where
/// their coverage changes. Returns false if a partner covered part of t.
bool cut_triangle(const Polygon& t, std::uint32_t id, PolygonCache& cache, CutScratch& cs);

}  // namespace ember::core
