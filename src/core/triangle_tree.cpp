// The Morton-ordered triangle tree (triangle_tree.hpp).
#include "core/triangle_tree.hpp"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_reduce.h>

#include <array>
#include <bit>
#include <cassert>
#include <cmath>
#include <limits>

#include "core/sort_pairs.hpp"

namespace ember::core {

namespace {

/// Twice a box's centre on axis a: lo + hi, in [-2^26, 2^26].
std::int64_t twice_centre(const Box32& b, int a) { return std::int64_t{b.lo[a]} + b.hi[a]; }

/// The triangles' Morton order: 10 bits per axis of the box centres within
/// their own bounding box (cubic cells, one shift for all axes), interleaved,
/// so neighbours in space are mostly neighbours in the order and
/// consecutive triangles make tight leaves. 30-bit keys take the radix sort
/// four passes where 21 bits per axis over the whole grid took eight (the
/// bunny pair's two trees: 7.8 M instructions of sorting); 2^30 cells stay
/// far finer than the triangles of the largest inputs (1.2M).
class MortonKeys {
 public:
  /// Keys within `bounds`, a box that holds every box to be keyed.
  explicit MortonKeys(const Box32& bounds) {
    std::int64_t range = 0;
    for (int a = 0; a < 3; ++a) {
      lo_[a] = std::int64_t{bounds.lo[a]} + bounds.lo[a];
      range = std::max(range, std::int64_t{bounds.hi[a]} + bounds.hi[a] - lo_[a]);
    }
    shift_ = std::max(0, static_cast<int>(std::bit_width(static_cast<std::uint64_t>(range))) - 10);
  }
  /// The cells' side (twice-centre units, as a shift): the keys' resolution.
  int shift() const { return shift_; }
  std::uint32_t operator()(const Box32& b) const {
    const auto spread = [](std::uint32_t v) {  // 10 bits -> every third of 30
      v = (v | v << 16) & 0x030000ffu;
      v = (v | v << 8) & 0x0300f00fu;
      v = (v | v << 4) & 0x030c30c3u;
      v = (v | v << 2) & 0x09249249u;
      return v;
    };
    std::uint32_t key = 0;
    for (int a = 0; a < 3; ++a)
      key |= spread(static_cast<std::uint32_t>((twice_centre(b, a) - lo_[a]) >> shift_)) << a;
    return key;
  }

 private:
  std::array<std::int64_t, 3> lo_;
  int shift_ = 0;
};

/// The bounding box of `boxes` (an empty box, lo > hi, is neutral for add()).
Box32 bounds_of(std::span<const Box32> boxes) {
  return tbb::parallel_reduce(
      tbb::blocked_range<std::size_t>(0, boxes.size(), 4096), Box32{},
      [&](const tbb::blocked_range<std::size_t>& r, Box32 acc) {
        for (std::size_t i = r.begin(); i != r.end(); ++i) acc.add(boxes[i]);
        return acc;
      },
      [](Box32 x, const Box32& y) {
        x.add(y);
        return x;
      });
}

}  // namespace

bool box_clearly_beside(const Box32& box, const IntPoint& o, const std::array<std::int64_t, 3>& n) {
  // Box corners minus o are below 2^27 and the normal's components below
  // 2^53: both exact in double. Each product (< 2^80) is rounded once, and
  // each extreme (the sum over the axes of the larger, or the smaller,
  // product) twice more: its error is below 3.01 * 2^-53 of the products'
  // magnitudes, which the margin of 2^-50 of them covers. Rounding is
  // monotone, so the larger rounded product is the rounded larger one.
  static_assert(kCoordLimit <= (std::int64_t{1} << 25) && 2 * kCoordLimit + 1 < (std::int64_t{1} << 53),
                "box corner - o is exact in double");
  const double origin[3] = {static_cast<double>(o.x), static_cast<double>(o.y), static_cast<double>(o.z)};
  double most = 0, least = 0, size = 0;
  for (std::size_t k = 0; k < 3; ++k) {
    const double nk = static_cast<double>(n[k]);
    const double lo = nk * (box.lo[k] - origin[k]), hi = nk * (box.hi[k] - origin[k]);
    most += std::max(lo, hi);
    least += std::min(lo, hi);
    size += std::max(std::abs(lo), std::abs(hi));
  }
  const double margin = size * 0x1p-50;
  return most < -margin || least > margin;
}

Box32 box_of(const std::array<IntPoint, 3>& t) {
  // Each axis from its three values directly (|x| <= 2^25 fits int32): the
  // loop from an empty box cost ~57 instructions per triangle, and every
  // input triangle passes here for the operand trees.
  const auto axis = [&](std::int64_t IntPoint::*c, int a, Box32& b) {
    const std::int64_t x = t[0].*c, y = t[1].*c, z = t[2].*c;
    b.lo[a] = static_cast<std::int32_t>(std::min(std::min(x, y), z));
    b.hi[a] = static_cast<std::int32_t>(std::max(std::max(x, y), z));
  };
  Box32 b;
  axis(&IntPoint::x, 0, b);
  axis(&IntPoint::y, 1, b);
  axis(&IntPoint::z, 2, b);
  return b;
}

Box32 enclosing_box(const std::array<double, 3>& lo, const std::array<double, 3>& hi) {
  constexpr double kMin = std::numeric_limits<std::int32_t>::min(), kMax = std::numeric_limits<std::int32_t>::max();
  Box32 b;
  for (int a = 0; a < 3; ++a) {
    b.lo[a] = static_cast<std::int32_t>(std::clamp(std::floor(lo[a]), kMin, kMax));
    b.hi[a] = static_cast<std::int32_t>(std::clamp(std::ceil(hi[a]), kMin, kMax));
  }
  return b;
}

TriangleTree::TriangleTree(std::span<const Box32> boxes) : TriangleTree(boxes, bounds_of(boxes)) {}

TriangleTree::TriangleTree(std::span<const Box32> boxes, const Box32& key_bounds) : key_bounds_(key_bounds) {
  const std::size_t n = boxes.size();
  const MortonKeys morton_key(key_bounds);
  FillVector<std::pair<std::uint32_t, std::uint32_t>> order(n);  // every slot written below
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, 4096), [&](const tbb::blocked_range<std::size_t>& r) {
    for (std::size_t i = r.begin(); i != r.end(); ++i) order[i] = {morton_key(boxes[i]), static_cast<std::uint32_t>(i)};
  });
  sort_pairs(order);  // keys tie-broken by index: one order for any thread count
  item_.resize(n);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, 4096), [&](const tbb::blocked_range<std::size_t>& r) {
    for (std::size_t i = r.begin(); i != r.end(); ++i) item_[i] = order[i].second;
  });
  lay_out([&](std::size_t slot) { return boxes[item_[slot]]; });
}

bool TriangleTree::same_cell_size(const Box32& a, const Box32& b) {
  return MortonKeys(a).shift() == MortonKeys(b).shift();
}

Box32 TriangleTree::bounds(std::span<const Box32> boxes) { return bounds_of(boxes); }

TriangleTree TriangleTree::merged(const TriangleTree& a, const TriangleTree& b) {
  assert(a.key_bounds_ == b.key_bounds_);
  const auto b_base = static_cast<std::uint32_t>(a.size());
  TriangleTree t;
  t.key_bounds_ = a.key_bounds_;
  const MortonKeys key(a.key_bounds_);
  // Slot i of the merge takes a's item or b's (shifted) by (key, id): ties
  // go to a, whose ids are below b's. In blocks of a's slots, each with the
  // slots of b that sort before its end (found by binary search), merged in
  // parallel.
  // Each side's (key, id) in its order: ascending, ids unique.
  using Keyed = std::pair<std::uint32_t, std::uint32_t>;
  const auto keyed = [&](const TriangleTree& tree, std::uint32_t base) {
    FillVector<Keyed> k(tree.size());  // every entry written below
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, tree.size(), 4096), [&](const tbb::blocked_range<std::size_t>& r) {
      for (std::size_t s = r.begin(); s != r.end(); ++s) k[s] = {key(tree.box(s)), base + tree.item(s)};
    });
    return k;
  };
  const FillVector<Keyed> ka = keyed(a, 0), kb = keyed(b, b_base);
  // Ties of keys go to a, whose ids are below b's. In blocks of a's slots,
  // each with the slots of b that sort before its end (binary search),
  // merged in parallel: the result does not depend on the schedule.
  constexpr std::size_t kBlock = 16384;
  const std::size_t blocks = std::max<std::size_t>(1, (ka.size() + kBlock - 1) / kBlock);
  const auto b_before = [&](std::size_t i) {  // b's slots that sort before a's slot i (all of b past a's end)
    return i == ka.size() ? kb.size() : static_cast<std::size_t>(std::lower_bound(kb.begin(), kb.end(), ka[i]) - kb.begin());
  };
  // from[s]: the slot of a (below a.size()) or of b (a.size() + slot) that
  // slot s of the merge takes, for its box.
  const std::size_t n = a.size() + b.size();
  t.item_.resize(n);
  FillVector<std::uint32_t> from(n);  // every entry written below
  tbb::parallel_for(std::size_t{0}, blocks, [&](std::size_t k) {
    std::size_t i = k * kBlock, j = k == 0 ? 0 : b_before(i);
    const std::size_t i_end = std::min(ka.size(), (k + 1) * kBlock), j_end = b_before(i_end);
    for (std::size_t out = i + j; i < i_end || j < j_end; ++out) {
      const bool take_a = j == j_end || (i < i_end && ka[i] < kb[j]);
      const std::size_t slot = take_a ? i++ : a.size() + j++;
      t.item_[out] = take_a ? ka[slot].second : kb[slot - a.size()].second;
      from[out] = static_cast<std::uint32_t>(slot);
    }
  });
  t.lay_out([&](std::size_t slot) { return from[slot] < a.size() ? a.box(from[slot]) : b.box(from[slot] - a.size()); });
  return t;
}

template <typename BoxOfSlot>
void TriangleTree::lay_out(BoxOfSlot&& box_of_slot) {
  const std::size_t n = item_.size();
  leaves_ = std::bit_ceil(std::max<std::size_t>(1, (n + kLeaf - 1) / kLeaf));
  depth_ = std::countr_zero(leaves_);
  node_.assign(2 * leaves_ - 1, Box32{});
  // Slots past the last triangle are empty boxes and meet nothing.
  const std::size_t first = first_leaf(), used = (n + kLeaf - 1) / kLeaf;
  block_.resize(used);
  tbb::parallel_for(std::size_t{0}, used, [&](std::size_t k) {
    LeafBlock& block = block_[k];
    for (std::size_t s = 0; s < kLeaf; ++s) {
      const std::size_t i = k * kLeaf + s;
      const Box32 b = i < n ? box_of_slot(i) : Box32{};
      for (int a = 0; a < 3; ++a) {
        block.lo[a][s] = b.lo[a];
        block.hi[a][s] = b.hi[a];
      }
      node_[first + k].add(b);
    }
  });
  for (int d = depth_ - 1; d >= 0; --d) {
    const std::size_t level = (std::size_t{1} << d) - 1, count = std::size_t{1} << d;
    tbb::parallel_for(tbb::blocked_range<std::size_t>(level, level + count, 1024),
                      [&](const tbb::blocked_range<std::size_t>& r) {
                        for (std::size_t i = r.begin(); i != r.end(); ++i) {
                          node_[i] = node_[2 * i + 1];
                          node_[i].add(node_[2 * i + 2]);
                        }
                      });
  }
}

}  // namespace ember::core
