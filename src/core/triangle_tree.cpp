// The Morton-ordered triangle tree (triangle_tree.hpp).
#include "core/triangle_tree.hpp"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <bit>
#include <cmath>

#include "core/sort_pairs.hpp"

namespace ember::core {

namespace {

/// 21 bits per axis of the box centre, interleaved: neighbours in space are
/// mostly neighbours in the order, so consecutive triangles make tight leaves.
std::uint64_t morton_key(const Box32& b) {
  const auto spread = [](std::uint64_t v) {  // 21 bits -> every third of 63
    v &= 0x1fffff;
    v = (v | v << 32) & 0x1f00000000ffffULL;
    v = (v | v << 16) & 0x1f0000ff0000ffULL;
    v = (v | v << 8) & 0x100f00f00f00f00fULL;
    v = (v | v << 4) & 0x10c30c30c30c30c3ULL;
    v = (v | v << 2) & 0x1249249249249249ULL;
    return v;
  };
  std::uint64_t key = 0;
  for (int a = 0; a < 3; ++a) {
    // lo + hi is in [-2^26, 2^26]; shifted to [0, 2^27] and cut to 21 bits.
    const std::int64_t twice_centre = std::int64_t{b.lo[a]} + b.hi[a] + (std::int64_t{1} << 26);
    key |= spread(static_cast<std::uint64_t>(std::min<std::int64_t>(twice_centre >> 6, 0x1fffff))) << a;
  }
  return key;
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
  Box32 b;
  for (const IntPoint& p : t) {
    const std::int64_t c[3] = {p.x, p.y, p.z};
    for (int a = 0; a < 3; ++a) {
      b.lo[a] = std::min(b.lo[a], static_cast<std::int32_t>(c[a]));
      b.hi[a] = std::max(b.hi[a], static_cast<std::int32_t>(c[a]));
    }
  }
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

TriangleTree::TriangleTree(std::span<const Box32> boxes) {
  const std::size_t n = boxes.size();
  FillVector<std::pair<std::uint64_t, std::uint32_t>> order(n);  // every slot written below
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
