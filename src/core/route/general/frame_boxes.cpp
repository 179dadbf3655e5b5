// Boxes in a leaf's principal frame (see the header for why they are sound).
#include "core/route/general/frame_boxes.hpp"

#include <algorithm>
#include <bit>
#include <cmath>

namespace ember::core {

namespace {

using V3 = std::array<double, 3>;

/// Calls store(i, lo, hi) with polygon i's interval along u (a frame axis),
/// measured from c and padded by `pad` (see the header for why it is sound).
template <typename Store>
void intervals_along(const SoupApprox& a, std::size_t n, const V3& u, const V3& c, double pad, Store&& store) {
  for (std::size_t i = 0; i < n; ++i) {
    double lo = HUGE_VAL, hi = -HUGE_VAL;
    for (const V3& p : a.of(i)) {
      const double r = u[0] * (p[0] - c[0]) + u[1] * (p[1] - c[1]) + u[2] * (p[2] - c[2]);
      lo = std::min(lo, r - pad);
      hi = std::max(hi, r + pad);
    }
    store(i, lo, hi);
  }
}

/// Widens [l, h] to hold [lo, hi]. A NaN bound sticks: apart() holds no
/// box with a NaN bound apart from any other, nor may a block that holds one.
void widen(double& l, double& h, double lo, double hi) {
  if (!std::isnan(l)) l = lo < l || std::isnan(lo) ? lo : l;
  if (!std::isnan(h)) h = hi > h || std::isnan(hi) ? hi : h;
}

/// The two operands with the most polygons (most first, ties to the lower
/// operand), or fewer where fewer are present.
std::vector<std::uint32_t> two_largest_operands(std::span<const std::uint32_t> operand) {
  std::vector<std::size_t> count;
  for (const std::uint32_t o : operand) {
    if (o >= count.size()) count.resize(o + 1, 0);
    ++count[o];
  }
  std::vector<std::uint32_t> top;
  for (int k = 0; k < 2; ++k) {
    std::uint32_t best = 0;
    for (std::uint32_t o = 1; o < count.size(); ++o)
      if (count[o] > count[best]) best = o;
    if (count.empty() || count[best] == 0) break;
    top.push_back(best);
    count[best] = 0;
  }
  return top;
}

}  // namespace

FrameBoxes::FrameBoxes(const SoupApprox& a, std::span<const std::uint32_t> operand) {
  const std::size_t n = a.begin.empty() ? 0 : a.begin.size() - 1;
  if (n == 0) return;
  // Any frame is sound; the principal one makes the boxes of a pile's
  // slivers thin across it.
  FrameAxes frame;
  if (!principal_frame(a.verts, frame)) return;
  V3 c{};
  double m = 0;
  for (const V3& p : a.verts)
    for (int k = 0; k < 3; ++k) m = std::max(m, std::fabs(p[k]));
  if (!a.verts.empty()) c = a.verts.front();
  for (double x : c) m = std::max(m, std::fabs(x));
  if (!std::isfinite(m)) return;
  const double pad = 0x1p-40 * m;
  for (int k = 0; k < 3; ++k) {
    lo_[k].resize(n);
    hi_[k].resize(n);
    intervals_along(a, n, frame[k], c, pad, [&](std::size_t i, double lo, double hi) {
      lo_[k][i] = lo;
      hi_[k][i] = hi;
    });
  }
  build_grid();
  build_blocks();
  if (operand.size() != n) return;
  const std::vector<std::uint32_t> top = two_largest_operands(operand);
  if (top.size() < 2) return;
  operand_boxes_.resize(n);
  for (std::size_t f = 0; f < 2; ++f) {
    std::vector<V3> own;
    for (std::size_t i = 0; i < n; ++i)
      if (operand[i] == top[f]) own.insert(own.end(), a.of(i).begin(), a.of(i).end());
    FrameAxes of_operand;
    if (!principal_frame(own, of_operand)) {
      operand_boxes_.clear();
      return;
    }
    for (std::size_t axis = 1; axis < 3; ++axis)
      intervals_along(a, n, of_operand[axis], c, pad, [&](std::size_t i, double lo, double hi) {
        operand_boxes_[i].lo[2 * f + axis - 1] = lo;
        operand_boxes_[i].hi[2 * f + axis - 1] = hi;
      });
  }
  OperandBoxes empty;
  empty.lo.fill(HUGE_VAL);
  empty.hi.fill(-HUGE_VAL);
  block_operand_boxes_.assign((n + kBlock - 1) / kBlock, empty);
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t k = 0; k < 4; ++k)
      widen(block_operand_boxes_[i / kBlock].lo[k], block_operand_boxes_[i / kBlock].hi[k], operand_boxes_[i].lo[k],
            operand_boxes_[i].hi[k]);
}

namespace {
constexpr int kMaxCells = 32;  // per axis: a pile of ~5,000 thin polygons gets ~5 per cell
constexpr int kMinCells = 4;
constexpr int kMaxSpan = 64;  // cells a polygon may cover before it counts as wide
/// The grid is coarsened until polygons cover at most this many cells on
/// average (wide ones counted as kMaxSpan + 1): the cost is flat for small
/// values and grows once a query marks each candidate many times.
constexpr std::size_t kMeanSpan = 4;
/// candidates() scans rather than asks a grid of at most this many cells
/// per axis, where four boxes go in one compare (AVX2): in so coarse a grid
/// a query's marks and readback visit a large part of the leaf one polygon
/// at a time, more than the scan costs (which also skips blocks:
/// FrameBoxes::kBlock). Without AVX2 the scalar scan is slower than the
/// grid.
constexpr int kScanCells = 8;
}  // namespace

void FrameBoxes::build_blocks() {
  const std::size_t n = lo_[0].size(), blocks = (n + kBlock - 1) / kBlock;
  for (int k = 0; k < 3; ++k) {
    block_lo_[k].assign(blocks, HUGE_VAL);
    block_hi_[k].assign(blocks, -HUGE_VAL);
    for (std::size_t i = 0; i < n; ++i) widen(block_lo_[k][i / kBlock], block_hi_[k][i / kBlock], lo_[k][i], hi_[k][i]);
  }
}

std::array<int, 2> FrameBoxes::cell_range(std::size_t i, int axis) const {
  const std::vector<double>& cuts = cuts_[axis];
  // Cell c covers [cuts[c-1], cuts[c]] (closed: a box touching a cut is in both).
  const auto first = std::lower_bound(cuts.begin(), cuts.end(), lo_[axis + 1][i]) - cuts.begin();
  const auto last = std::upper_bound(cuts.begin(), cuts.end(), hi_[axis + 1][i]) - cuts.begin();
  return {static_cast<int>(first), static_cast<int>(last)};
}

void FrameBoxes::build_grid() {
  const std::size_t n = lo_[0].size();
  std::array<std::vector<double>, 2> centre;
  for (int axis = 0; axis < 2; ++axis) {
    centre[axis].resize(n);
    for (std::size_t i = 0; i < n; ++i) centre[axis][i] = 0.5 * (lo_[axis + 1][i] + hi_[axis + 1][i]);
    std::sort(centre[axis].begin(), centre[axis].end());
  }
  // A grid finer than about 2 sqrt(n) cells per axis leaves most cells of a
  // small leaf empty and its polygons spanning many: start no finer.
  const int first = std::clamp(static_cast<int>(std::bit_floor(static_cast<unsigned>(2 * std::sqrt(double(n))))),
                               kMinCells, kMaxCells);
  for (int k = first;; k /= 2) {
    for (int axis = 0; axis < 2; ++axis) {
      std::vector<double>& cuts = cuts_[axis];
      cuts.clear();
      for (int c = 1; c < k; ++c) cuts.push_back(centre[axis][n * static_cast<std::size_t>(c) / k]);
      cuts.erase(std::unique(cuts.begin(), cuts.end()), cuts.end());
    }
    if (k <= kMinCells) break;
    std::size_t covered = 0;
    for (std::size_t i = 0; i < n; ++i) {
      const auto r0 = cell_range(i, 0), r1 = cell_range(i, 1);
      covered += static_cast<std::size_t>(std::min((r0[1] - r0[0] + 1) * (r1[1] - r1[0] + 1), kMaxSpan + 1));
    }
    if (covered <= kMeanSpan * n) break;
  }
  scan_first_ = cpu_has_avx2() && grid_cells()[0] <= kScanCells && grid_cells()[1] <= kScanCells;
  const auto columns = static_cast<std::size_t>(cuts_[1].size() + 1);
  const std::size_t cells = (cuts_[0].size() + 1) * columns;
  cell_begin_.assign(cells + 1, 0);
  std::vector<std::array<int, 4>> range(n);
  for (std::size_t i = 0; i < n; ++i) {
    const auto r0 = cell_range(i, 0), r1 = cell_range(i, 1);
    range[i] = {r0[0], r0[1], r1[0], r1[1]};
    if ((r0[1] - r0[0] + 1) * (r1[1] - r1[0] + 1) > kMaxSpan) {
      wide_.push_back(static_cast<std::uint32_t>(i));
      range[i] = {1, 0, 1, 0};  // empty
      continue;
    }
    for (int a = r0[0]; a <= r0[1]; ++a)
      for (int b = r1[0]; b <= r1[1]; ++b) ++cell_begin_[static_cast<std::size_t>(a) * columns + b + 1];
  }
  for (int k = 0; k < 3; ++k)
    for (const std::uint32_t j : wide_) {
      wide_lo_[k].push_back(lo_[k][j]);
      wide_hi_[k].push_back(hi_[k][j]);
    }
  for (std::size_t c = 0; c < cells; ++c) cell_begin_[c + 1] += cell_begin_[c];
  members_.resize(cell_begin_.back());
  std::vector<std::uint32_t> fill(cell_begin_.begin(), cell_begin_.end() - 1);
  for (std::size_t i = 0; i < n; ++i)
    for (int a = range[i][0]; a <= range[i][1]; ++a)
      for (int b = range[i][2]; b <= range[i][3]; ++b)
        members_[fill[static_cast<std::size_t>(a) * columns + b]++] = static_cast<std::uint32_t>(i);
}

bool FrameBoxes::overlapping(std::size_t i, Query& query, Candidates& out) const {
  const auto r0 = cell_range(i, 0), r1 = cell_range(i, 1);
  if ((r0[1] - r0[0] + 1) * (r1[1] - r1[0] + 1) > kMaxSpan) return false;
  const std::size_t words = (lo_[0].size() + 63) / 64;
  if (query.marks.size() != words) query.marks.assign(words, 0);
  std::uint64_t* const marks = query.marks.data();
  const auto mark = [marks](std::uint32_t j, std::uint64_t bit) { marks[j >> 6] |= bit << (j & 63); };
  const auto columns = static_cast<std::size_t>(cuts_[1].size() + 1);
  for (int a = r0[0]; a <= r0[1]; ++a)
    for (int b = r1[0]; b <= r1[1]; ++b) {
      const std::size_t c = static_cast<std::size_t>(a) * columns + b;
      for (std::uint32_t k = cell_begin_[c]; k < cell_begin_[c + 1]; ++k) mark(members_[k], 1);
    }
  // The wide polygons are in no cell, and i is not wide (it would have been
  // declined above): one branch-free pass over their boxes, stored together
  // (in a pile leaf they can be a large part of it), marks those that
  // meet i's.
  out.clear();
  append_meeting(
      wide_lo_, wide_hi_, i, wide_.size(), [&](std::size_t k) { return wide_[k]; }, out);
  for (const std::uint32_t j : out) mark(j, 1);
  // Read back in ascending order (the order a full scan finds them in),
  // clearing every word; the wide ones that meet are tested again (few).
  out.clear();
  for (std::size_t w = 0; w < words; ++w) {
    for (std::uint64_t bits = marks[w]; bits != 0; bits &= bits - 1) {
      const auto j = static_cast<std::uint32_t>(64 * w + static_cast<std::size_t>(std::countr_zero(bits)));
      if (j != i && !apart(i, j)) out.push_back(j);
    }
    marks[w] = 0;
  }
  return true;
}

void FrameBoxes::scan(std::size_t i, Candidates& out) const {
#if EMBER_WIDE_LANES
  if (cpu_has_avx2()) return scan_avx2(i, out);
#endif
  scan_portable(i, out);
}

void FrameBoxes::scan_portable(std::size_t i, Candidates& out) const {
  out.clear();
  append_meeting(
      lo_, hi_, i, i, [](std::size_t j) { return static_cast<std::uint32_t>(j); }, out);
  if (!operand_boxes_.empty()) std::erase_if(out, [&](std::uint32_t j) { return apart_across(i, j); });
}

#if EMBER_WIDE_LANES
namespace {

/// Lanes k of the boxes (a, b) (four boxes along one axis) that do not lie
/// apart from [l, h]: "not greater" compares that hold for NaN, as apart()'s
/// negation does.
EMBER_TARGET_AVX2 inline __m256d meet4(const double* a, const double* b, __m256d l, __m256d h) {
  return _mm256_and_pd(_mm256_cmp_pd(_mm256_loadu_pd(a), h, _CMP_NGT_UQ),
                       _mm256_cmp_pd(l, _mm256_loadu_pd(b), _CMP_NGT_UQ));
}

}  // namespace

EMBER_TARGET_AVX2 inline bool FrameBoxes::apart_across_avx2(std::size_t i, std::size_t j) const {
  return apart_avx2(operand_boxes_[i], operand_boxes_[j]);
}

EMBER_TARGET_AVX2 inline bool FrameBoxes::apart_avx2(const OperandBoxes& a, const OperandBoxes& b) {
  const __m256d b_above = _mm256_cmp_pd(_mm256_load_pd(b.lo.data()), _mm256_load_pd(a.hi.data()), _CMP_GT_OQ);
  const __m256d a_above = _mm256_cmp_pd(_mm256_load_pd(a.lo.data()), _mm256_load_pd(b.hi.data()), _CMP_GT_OQ);
  return _mm256_movemask_pd(_mm256_or_pd(b_above, a_above)) != 0;
}

EMBER_TARGET_AVX2 void FrameBoxes::scan_avx2(std::size_t i, Candidates& out) const {
  const std::size_t n = lo_[0].size();
  out.resize(n);
  std::uint32_t* const dst = out.data();
  std::size_t count = 0;
  const bool across = !operand_boxes_.empty();
  const __m256d l0 = _mm256_set1_pd(lo_[0][i]), l1 = _mm256_set1_pd(lo_[1][i]), l2 = _mm256_set1_pd(lo_[2][i]);
  const __m256d h0 = _mm256_set1_pd(hi_[0][i]), h1 = _mm256_set1_pd(hi_[1][i]), h2 = _mm256_set1_pd(hi_[2][i]);
  for (std::size_t block = 0; block * kBlock < n; ++block) {
    // Blocks of consecutive polygons (neighbours in the mesh, mostly) whose
    // joint box lies apart from i's, in the leaf's frame or an operand's,
    // are skipped whole.
    if (block_lo_[0][block] > hi_[0][i] || lo_[0][i] > block_hi_[0][block] || block_lo_[1][block] > hi_[1][i] ||
        lo_[1][i] > block_hi_[1][block] || block_lo_[2][block] > hi_[2][i] || lo_[2][i] > block_hi_[2][block] ||
        (across && apart_avx2(operand_boxes_[i], block_operand_boxes_[block])))
      continue;
    const std::size_t end = std::min(n, (block + 1) * kBlock);
    for (std::size_t k = block * kBlock; k < end; k += 4) {
      // The last group of fewer than four is tested one by one.
      unsigned bits = 0;
      if (k + 4 <= end) {
        const __m256d m01 = _mm256_and_pd(meet4(&lo_[0][k], &hi_[0][k], l0, h0), meet4(&lo_[1][k], &hi_[1][k], l1, h1));
        bits = static_cast<unsigned>(_mm256_movemask_pd(_mm256_and_pd(m01, meet4(&lo_[2][k], &hi_[2][k], l2, h2))));
      } else {
        for (std::size_t r = k; r < end; ++r) bits |= static_cast<unsigned>(!apart_in_leaf_frame(i, r)) << (r - k);
      }
      // Each box the leaf frame keeps is written, then kept unless it is i's
      // or its operand-frame boxes lie apart from i's.
      for (; bits != 0; bits &= bits - 1) {
        const std::size_t j = k + static_cast<std::size_t>(std::countr_zero(bits));
        dst[count] = static_cast<std::uint32_t>(j);
        count += (j != i) & !(across && apart_across_avx2(i, j));
      }
    }
  }
  out.resize(count);
}
#endif

}  // namespace ember::core
