// The Morton-ordered triangle tree (triangle_tree.hpp).
#include "core/triangle_tree.hpp"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_reduce.h>

#include <array>
#include <bit>
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
  explicit MortonKeys(std::span<const Box32> boxes) {
    // Twice the centres lie in [2 lo, 2 hi] of all boxes together (an empty
    // box, lo > hi, is neutral for add()).
    const Box32 all = tbb::parallel_reduce(
        tbb::blocked_range<std::size_t>(0, boxes.size(), 4096), Box32{},
        [&](const tbb::blocked_range<std::size_t>& r, Box32 acc) {
          for (std::size_t i = r.begin(); i != r.end(); ++i) acc.add(boxes[i]);
          return acc;
        },
        [](Box32 x, const Box32& y) {
          x.add(y);
          return x;
        });
    std::int64_t range = 0;
    for (int a = 0; a < 3; ++a) {
      lo_[a] = std::int64_t{all.lo[a]} + all.lo[a];
      range = std::max(range, std::int64_t{all.hi[a]} + all.hi[a] - lo_[a]);
    }
    shift_ = std::max(0, static_cast<int>(std::bit_width(static_cast<std::uint64_t>(range))) - 10);
  }
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
  constexpr double kMin = -kQueryLimit, kMax = kQueryLimit;
  Box32 b;
  for (int a = 0; a < 3; ++a) {
    b.lo[a] = static_cast<std::int32_t>(std::clamp(std::floor(lo[a]), kMin, kMax));
    b.hi[a] = static_cast<std::int32_t>(std::clamp(std::ceil(hi[a]), kMin, kMax));
  }
  return b;
}

TriangleTree::TriangleTree(std::span<const Box32> boxes) {
  const std::size_t n = boxes.size();
  const MortonKeys morton_key(boxes);
  FillVector<std::pair<std::uint32_t, std::uint32_t>> order(n);  // every slot written below
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, 4096), [&](const tbb::blocked_range<std::size_t>& r) {
    for (std::size_t i = r.begin(); i != r.end(); ++i) order[i] = {morton_key(boxes[i]), static_cast<std::uint32_t>(i)};
  });
  sort_pairs(order);  // keys tie-broken by index: one order for any thread count
  item_.resize(n);
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
      const Box32 b = i < n ? boxes[order[i].second] : Box32{};
      if (i < n) item_[i] = order[i].second;
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
