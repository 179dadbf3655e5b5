#pragma once
// Bounding boxes in a leaf's own principal frame, a filter for pile leaves.
//
// A pile of long slivers along a diagonal (such as thin rods whose sides are
// strips thousands of units long and a few grid steps wide) puts
// thousands of strips into every axis-aligned box, and their axis-aligned
// boxes all overlap. Seen along the pile's principal direction the strips are
// thin: boxes in a frame whose first axis follows the pile separate them.
//
// Soundness: the frame R is a double matrix, taken as an exact linear map.
// Two polygons that share a point p have the exact point R (p - c) in both of
// their exact frame boxes (a linear map keeps a convex hull inside the box of
// its images). The computed boxes start from vertex approximations (within
// 2^-50 relative, Point::f) and round a few times: each frame coordinate errs
// by less than 2^-46 M, M the largest |coordinate| of the leaf and of c
// (|R_kj| <= 1); the boxes are padded by 2^-40 M. So polygons whose padded
// boxes are apart cannot touch.
//
// A pile of two operands' slivers at a small angle to each other (twin rods
// a fraction of a degree apart) has one principal direction between
// theirs, in which each rod's strips drift across the section by tens of
// grid units over their length, and their boxes overlap hundreds of others.
// Each operand's own principal frame keeps its own strips thin: two
// polygons whose boxes are apart in any of the frames cannot touch, so the
// operands' frames filter the leaf frame's answers, removing a good part of
// the candidates in such a pile's largest leaves.
#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "core/support/fill_vector.hpp"
#include "core/support/principal_frame.hpp"
#include "core/model/soup.hpp"
#include "core/support/wide_lanes.hpp"

namespace ember::core {

class FrameBoxes {
 public:
  FrameBoxes() = default;
  /// Boxes of the polygons that `a` approximates, in the principal frame of
  /// their vertices; with `operand` (polygon i's operand, for every polygon)
  /// also in the principal frames of the two operands with the most polygons,
  /// where the leaf holds more than one.
  explicit FrameBoxes(const SoupApprox& a, std::span<const std::uint32_t> operand = {});

  bool empty() const { return lo_[0].empty(); }
  /// A query's answer: polygon indices, written without zero-filling first
  /// (a scan sizes the buffer for every polygon of the leaf, then keeps the
  /// few that meet: zeroing it would touch every slot for a few answers).
  using Candidates = FillVector<std::uint32_t>;
  /// A caller's memory of which polygons its current query has found: one per
  /// thread, so that the threads of a pile leaf query one FrameBoxes together.
  struct Query {
    /// One bit per polygon, all clear between queries: a query marks the
    /// members of the cells it visits (each once, however many cells hold
    /// it) and reads them back in ascending order, clearing as it goes: the
    /// answer comes out sorted, where a per-polygon stamp would need a sort
    /// of every answer, a large part of a pile's solve.
    std::vector<std::uint64_t> marks;
  };
  /// The polygons (ascending, without i) whose boxes overlap polygon i's, from a
  /// grid across the principal axis; false (out untouched) when i's box spans
  /// too much of the grid: the caller then calls scan().
  bool overlapping(std::size_t i, Query& query, Candidates& out) const;
  /// The same answer as overlapping() by testing every polygon, for the
  /// polygons overlapping() declines: one branch-free pass over the boxes
  /// stored axis by axis. In a pile of slivers many of the pile leaves'
  /// gathers are such scans, over thousands of polygons each; testing each
  /// polygon in gather instead (its soup entry, its world box, then its
  /// frame box) would make gather a large part of the pile's time.
  void scan(std::size_t i, Candidates& out) const;
  /// The same answer as scan(), one element at a time (any processor).
  void scan_portable(std::size_t i, Candidates& out) const;
#if EMBER_WIDE_LANES
  /// The same answer as scan(), four boxes per compare, skipping blocks of
  /// polygons apart from i: only where cpu_has_avx2().
  EMBER_TARGET_AVX2 void scan_avx2(std::size_t i, Candidates& out) const;
#endif
  /// The answer of overlapping() or scan(), whichever is cheaper for i here:
  /// where the grid coarsened to its fewest cells and the processor scans
  /// four boxes per compare, the scan (a coarse grid's query marks and reads
  /// back a large part of the leaf, one polygon at a time); otherwise the grid,
  /// unless it declines i.
  void candidates(std::size_t i, Query& query, Candidates& out) const {
    if (scan_first_ || !overlapping(i, query, out)) scan(i, out);
  }
  /// Whether candidates() scans every polygon (see there).
  bool scans_first() const { return scan_first_; }
  /// Cells per axis of the grid across the principal axis (after coarsening).
  std::array<int, 2> grid_cells() const {
    return {static_cast<int>(cuts_[0].size()) + 1, static_cast<int>(cuts_[1].size()) + 1};
  }
  /// True when polygons i and j cannot share a point: their boxes are apart
  /// in the leaf's frame or in an operand's.
  bool apart(std::size_t i, std::size_t j) const {
    return apart_in_leaf_frame(i, j) || (!operand_boxes_.empty() && apart_across(i, j));
  }
  /// Whether the boxes include the operands' frames (a leaf of two or more operands).
  bool has_operand_frames() const { return !operand_boxes_.empty(); }

 private:
  /// Polygon i's boxes across the principal axis of two operands' frames
  /// (axes 1 and 2 of each, in that order): one cache line per polygon, read
  /// for each candidate the leaf frame leaves. Their principal axes are within
  /// a degree of the leaf's, so axis 0 would separate little more.
  struct alignas(64) OperandBoxes {
    std::array<double, 4> lo, hi;
  };
  bool apart_in_leaf_frame(std::size_t i, std::size_t j) const {
    return lo_[0][j] > hi_[0][i] || lo_[0][i] > hi_[0][j] || lo_[1][j] > hi_[1][i] || lo_[1][i] > hi_[1][j] ||
           lo_[2][j] > hi_[2][i] || lo_[2][i] > hi_[2][j];
  }
  bool apart_across(std::size_t i, std::size_t j) const {
    const OperandBoxes &a = operand_boxes_[i], &b = operand_boxes_[j];
    bool apart = false;
    for (std::size_t k = 0; k < 4; ++k) apart |= (b.lo[k] > a.hi[k]) | (a.lo[k] > b.hi[k]);
    return apart;
  }
#if EMBER_WIDE_LANES
  EMBER_TARGET_AVX2 bool apart_across_avx2(std::size_t i, std::size_t j) const;
  EMBER_TARGET_AVX2 static bool apart_avx2(const OperandBoxes& a, const OperandBoxes& b);
#endif
  void build_grid();
  void build_blocks();
  std::array<int, 2> cell_range(std::size_t i, int axis) const;
  using AxisArrays = std::array<std::vector<double>, 3>;
  /// Appends id(k) for every box k of (lo, hi) but `skip` that meets polygon
  /// i's (not apart, see apart()), in order of k: one pass, written with &
  /// so that no branch depends on the boxes.
  template <typename Id>
  void append_meeting(const AxisArrays& lo, const AxisArrays& hi, std::size_t i, std::size_t skip, Id id,
                      Candidates& out) const {
    const std::size_t n = lo[0].size();
    std::size_t count = out.size();
    out.resize(count + n);
    const double l0 = lo_[0][i], l1 = lo_[1][i], l2 = lo_[2][i], h0 = hi_[0][i], h1 = hi_[1][i], h2 = hi_[2][i];
    const double *a0 = lo[0].data(), *a1 = lo[1].data(), *a2 = lo[2].data();
    const double *b0 = hi[0].data(), *b1 = hi[1].data(), *b2 = hi[2].data();
    for (std::size_t k = 0; k < n; ++k) {
      // Written as "not apart" (apart() verbatim, negated), so that a NaN
      // bound keeps a pair, as apart() does, rather than dropping it.
      const bool meet = !(a0[k] > h0) & !(l0 > b0[k]) & !(a1[k] > h1) & !(l1 > b1[k]) & !(a2[k] > h2) & !(l2 > b2[k]);
      out[count] = id(k);
      count += meet & (k != skip);
    }
    out.resize(count);
  }

  /// Per frame axis, every polygon's box (lo_[k][i], hi_[k][i]).
  AxisArrays lo_, hi_;
  AxisArrays wide_lo_, wide_hi_;  ///< the boxes of wide_[k], per axis
  /// The grid across the principal axis: cell boundaries at quantiles of the
  /// polygons' centres on frame axes 1 and 2 (dense where the polygons are),
  /// members per cell in CSR form; polygons spanning many cells are `wide_`.
  /// 32 cells per axis, halved (down to 4) while the polygons cover more
  /// than 4 cells on average: a query marks every member of every cell it
  /// covers, so a grid finer than the polygons marks each candidate many
  /// times (at 32 cells per axis a sliver covers dozens of cells, so a query
  /// makes many marks per candidate; a coarser grid makes few).
  std::array<std::vector<double>, 2> cuts_;
  std::vector<std::uint32_t> cell_begin_, members_, wide_;
  std::vector<OperandBoxes> operand_boxes_;  ///< empty for a leaf of one operand
  bool scan_first_ = false;                  ///< see candidates()
  /// The joint box of each block of kBlock consecutive polygons, per axis:
  /// scan_avx2 skips blocks apart from the query's box. Consecutive polygons
  /// are mostly neighbours in their mesh, so many blocks lie apart from a
  /// query. 32 polygons a block: smaller blocks spend more on the joint
  /// boxes, and larger ones gain almost nothing more.
  static constexpr std::size_t kBlock = 32;
  static_assert(kBlock % 4 == 0, "scan_avx2 tests whole groups of four within a block");
  AxisArrays block_lo_, block_hi_;
  std::vector<OperandBoxes> block_operand_boxes_;  ///< per block, where operand_boxes_ is not empty
};

}  // namespace ember::core
