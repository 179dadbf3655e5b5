#pragma once
// The vertices of a large loop in a uniform grid over the two axes its box
// spans most, for the ear clipper's emptiness test (region_triangulation.cpp): every
// ear test scanning the whole loop would make a region of n vertices cost
// O(n^2) box tests, which dominates the direct route where large triangles
// of one operand are cut by hundreds of the other operand's slivers. The
// grid only narrows which
// vertices are tested: the caller applies the same tests to each, so the
// ears, and the triangles, are the same.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <span>
#include <vector>

namespace ember::core {

class LoopGrid {
 public:
  /// Over the points at(0 .. n - 1) (double approximations).
  template <typename At>
  LoopGrid(std::size_t n, At&& at) {
    std::array<double, 3> lo{at(0)}, hi{at(0)};
    for (std::size_t i = 1; i < n; ++i)
      for (int a = 0; a < 3; ++a) {
        lo[a] = std::min(lo[a], at(i)[a]);
        hi[a] = std::max(hi[a], at(i)[a]);
      }
    std::array<int, 3> order{0, 1, 2};
    std::sort(order.begin(), order.end(), [&](int x, int y) { return hi[x] - lo[x] > hi[y] - lo[y]; });
    // About two points per cell.
    const int side = std::max(1, static_cast<int>(std::sqrt(static_cast<double>(n) / 2)));
    for (int d = 0; d < 2; ++d) {
      axis_[d] = order[d];
      origin_[d] = lo[axis_[d]];
      const double extent = hi[axis_[d]] - lo[axis_[d]];
      scale_[d] = extent > 0 ? side / extent : 0;
    }
    side_ = side;
    start_.assign(static_cast<std::size_t>(side) * side + 1, 0);
    cell_.resize(n);
    for (std::size_t i = 0; i < n; ++i) {
      cell_[i] = cell_of(at(i));
      ++start_[cell_[i] + 1];
    }
    for (std::size_t c = 1; c < start_.size(); ++c) start_[c] += start_[c - 1];
    items_.resize(n);
    slot_.resize(n);
    end_.assign(start_.begin(), start_.end() - 1);
    for (std::size_t i = 0; i < n; ++i) {
      slot_[i] = end_[cell_[i]]++;
      items_[slot_[i]] = static_cast<std::uint32_t>(i);
    }
  }

  /// Takes point i out of its cell (the ear clipper's clipped vertices,
  /// which the grid would otherwise keep offering to every later query).
  /// The last point of the cell takes its slot; `any` does not depend on
  /// the order in which a cell offers its points.
  void remove(std::uint32_t i) {
    const std::uint32_t last = --end_[cell_[i]], moved = items_[last];
    items_[slot_[i]] = moved;
    slot_[moved] = slot_[i];
    items_[last] = i;
    slot_[i] = last;
  }

  /// Whether f(i) holds for some point i offered for the box [lo, hi]: every
  /// point not removed that lies within 2^-30 of the box's magnitude of it
  /// along the grid's axes is offered (some others too). The ear test's
  /// double filter keeps points within 2^-39 (region_triangulation.cpp), and the
  /// grid's cell index is monotone
  /// in the coordinate (rounded subtraction and multiplication are), so the
  /// widened box's cells hold every point the filter keeps.
  template <typename F>
  bool any(const std::array<double, 3>& lo, const std::array<double, 3>& hi, F&& f) const {
    std::array<int, 2> first{}, last{};
    for (int d = 0; d < 2; ++d) {
      const int a = axis_[d];
      const double pad = 0x1p-30 * std::max(std::fabs(lo[a]), std::fabs(hi[a]));
      first[d] = index(lo[a] - pad, d);
      last[d] = index(hi[a] + pad, d);
    }
    for (int v = first[1]; v <= last[1]; ++v)
      for (int u = first[0]; u <= last[0]; ++u) {
        const std::size_t c = static_cast<std::size_t>(v) * side_ + u;
        for (std::uint32_t s = start_[c]; s < end_[c]; ++s)
          if (f(items_[s])) return true;
      }
    return false;
  }

 private:
  int index(double x, int d) const {
    const double t = (x - origin_[d]) * scale_[d];
    if (!(t > 0)) return 0;  // also NaN
    return t >= side_ ? side_ - 1 : static_cast<int>(t);
  }
  std::uint32_t cell_of(const std::array<double, 3>& p) const {
    return static_cast<std::uint32_t>(index(p[axis_[1]], 1) * side_ + index(p[axis_[0]], 0));
  }

  std::array<int, 2> axis_{};
  std::array<double, 2> origin_{}, scale_{};
  int side_ = 1;
  std::vector<std::uint32_t> start_, end_;          // a cell's points: items_[start_[c], end_[c])
  std::vector<std::uint32_t> items_, slot_, cell_;  // slot_[i]: i's place in items_; cell_[i]: its cell
};

}  // namespace ember::core
