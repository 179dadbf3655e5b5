// The Hilbert-ordered triangle tree (triangle_tree.hpp).
#include "core/search/triangle_tree.hpp"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_reduce.h>

#include <array>
#include <bit>
#include <cmath>
#include <limits>

#include "core/support/sort_pairs.hpp"

namespace ember::core {

namespace {

/// Twice a box's centre on axis a: lo + hi, in [-2^26, 2^26].
std::int64_t twice_centre(const Box32& b, int a) { return std::int64_t{b.lo[a]} + b.hi[a]; }

/// One level of a 3D Hilbert curve (Skilling's, "Programming the Hilbert
/// curve", 2004): for each of its 24 orientations (states) and each octant
/// of a cell (x at bit 0, y at bit 1, z at bit 2, as in a Morton code), the
/// octant's place along the curve (bits 0-2) and the orientation of the
/// curve inside it (bits 3-7). Derived from Skilling's transform by
/// following each orientation's octants to the orientations they hold;
/// tests/core/triangle_tree_test.cpp checks it against that transform and
/// that consecutive cells along it are face neighbours.
constexpr std::uint8_t kHilbertLevel[24][8] = {
    {8, 39, 27, 52, 17, 46, 2, 5},
    {56, 91, 73, 10, 71, 20, 86, 13},
    {48, 115, 103, 12, 1, 18, 110, 21},
    {126, 79, 29, 140, 129, 80, 26, 3},
    {148, 127, 37, 78, 43, 128, 34, 81},
    {156, 31, 35, 160, 45, 6, 42, 105},
    {72, 57, 139, 50, 87, 70, 4, 53},
    {0, 49, 111, 102, 171, 58, 76, 61},
    {180, 69, 83, 66, 143, 54, 184, 97},
    {16, 47, 9, 38, 123, 60, 74, 77},
    {132, 67, 85, 82, 95, 144, 14, 33},
    {142, 93, 185, 90, 55, 116, 96, 11},
    {188, 101, 175, 62, 107, 98, 176, 65},
    {164, 99, 119, 152, 109, 106, 22, 41},
    {174, 117, 63, 92, 177, 114, 64, 19},
    {30, 7, 161, 104, 125, 172, 122, 75},
    {130, 179, 133, 84, 25, 136, 166, 191},
    {94, 145, 141, 138, 15, 32, 28, 51},
    {146, 137, 149, 190, 155, 24, 36, 167},
    {154, 169, 147, 120, 157, 182, 44, 135},
    {162, 187, 121, 168, 165, 108, 134, 183},
    {118, 153, 23, 40, 173, 170, 124, 59},
    {178, 181, 131, 68, 113, 158, 88, 151},
    {186, 189, 89, 150, 163, 100, 112, 159},
};

/// Two levels at once: for state s and six Morton bits (the upper level's
/// octant in bits 3-5), the two places (bits 0-5) and the state after them
/// times 64 (bits 6-10), so the next lookup's row is the entry's high bits.
constexpr std::array<std::uint16_t, 24 * 64> two_hilbert_levels() {
  std::array<std::uint16_t, 24 * 64> t{};
  for (unsigned s = 0; s < 24; ++s)
    for (unsigned bits = 0; bits < 64; ++bits) {
      const unsigned upper = kHilbertLevel[s][bits >> 3];
      const unsigned lower = kHilbertLevel[upper >> 3][bits & 7];
      t[s * 64 + bits] = static_cast<std::uint16_t>((lower >> 3) << 6 | (upper & 7) << 3 | (lower & 7));
    }
  return t;
}
constexpr std::array<std::uint16_t, 24 * 64> kTwoHilbertLevels = two_hilbert_levels();

/// hilbert_key, inlined into the tree's key loop (as a call: ~20 more
/// instructions per triangle).
[[gnu::always_inline]] inline std::uint32_t curve_place(std::uint32_t x, std::uint32_t y, std::uint32_t z) {
  const auto spread = [](std::uint32_t v) {  // 10 bits -> every third of 30
    v = (v | v << 16) & 0x030000ffu;
    v = (v | v << 8) & 0x0300f00fu;
    v = (v | v << 4) & 0x030c30c3u;
    v = (v | v << 2) & 0x09249249u;
    return v;
  };
  const std::uint32_t morton = spread(x) | spread(y) << 1 | spread(z) << 2;
  std::uint32_t key = 0, row = 0;  // row: the state times 64
  for (int shift = 24; shift >= 0; shift -= 6) {
    const std::uint32_t entry = kTwoHilbertLevels[row | (morton >> shift & 63u)];
    key = key << 6 | (entry & 63u);
    row = entry & ~63u;
  }
  return key;
}

/// The triangles' order along a Hilbert curve through their box centres:
/// 10 bits per axis within the boxes' own bounding box (cubic cells, one
/// shift for all axes), so consecutive triangles make tight leaves and
/// every run of leaves under a node is one connected stretch of the curve.
/// A Morton order, which jumps between distant cells at its octant
/// boundaries, makes looser leaves and nodes, which cost the partner and
/// contact searches far more than the curve's keys cost to compute. 30-bit
/// keys take the radix sort four passes; 2^30 cells stay far finer than the
/// triangles of inputs of millions of triangles.
class CurveKeys {
 public:
  explicit CurveKeys(std::span<const Box32> boxes) {
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
    const auto cell = [&](int a) { return static_cast<std::uint32_t>((twice_centre(b, a) - lo_[a]) >> shift_); };
    return curve_place(cell(0), cell(1), cell(2));
  }

 private:
  std::array<std::int64_t, 3> lo_;
  int shift_ = 0;
};

}  // namespace

std::uint32_t hilbert_key(std::uint32_t x, std::uint32_t y, std::uint32_t z) { return curve_place(x, y, z); }

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
  const CurveKeys curve_key(boxes);
  FillVector<std::pair<std::uint32_t, std::uint32_t>> order(n);  // every slot written below
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, 4096), [&](const tbb::blocked_range<std::size_t>& r) {
    for (std::size_t i = r.begin(); i != r.end(); ++i) order[i] = {curve_key(boxes[i]), static_cast<std::uint32_t>(i)};
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
