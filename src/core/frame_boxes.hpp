#pragma once
// Bounding boxes in a leaf's own principal frame, a filter for pile leaves.
//
// A pile of long slivers along a diagonal (the sliver pile: thin rods whose
// sides are strips thousands of units long and a few grid steps wide) puts
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
#include <array>
#include <cstdint>
#include <vector>

#include "core/soup.hpp"

namespace ember::core {

class FrameBoxes {
 public:
  FrameBoxes() = default;
  /// Boxes of the polygons that `a` approximates, in the principal frame of
  /// their vertices.
  explicit FrameBoxes(const SoupApprox& a);

  bool empty() const { return lo_.empty(); }
  /// A caller's memory of which polygons its current query has found: one per
  /// thread, so that the threads of a pile leaf query one FrameBoxes together.
  struct Query {
    std::vector<std::uint32_t> seen;  ///< per polygon: the query stamp that found it
    std::uint32_t stamp = 0;
  };
  /// The polygons (ascending, without i) whose boxes overlap polygon i's, from a
  /// grid across the principal axis; false (out untouched) when i's box spans
  /// too much of the grid, and the caller should test every polygon.
  bool overlapping(std::size_t i, Query& query, std::vector<std::uint32_t>& out) const;
  /// True when polygons i and j cannot share a point.
  bool apart(std::size_t i, std::size_t j) const {
    const std::array<double, 3>&li = lo_[i], &hi = hi_[i], &lj = lo_[j], &hj = hi_[j];
    return hi[0] < lj[0] || hj[0] < li[0] || hi[1] < lj[1] || hj[1] < li[1] || hi[2] < lj[2] || hj[2] < li[2];
  }

 private:
  void build_grid();
  std::array<int, 2> cell_range(std::size_t i, int axis) const;

  std::vector<std::array<double, 3>> lo_, hi_;
  /// The grid across the principal axis: cell boundaries at quantiles of the
  /// polygons' centres on frame axes 1 and 2 (dense where the polygons are),
  /// members per cell in CSR form; polygons spanning many cells are `wide_`.
  std::array<std::vector<double>, 2> cuts_;
  std::vector<std::uint32_t> cell_begin_, members_, wide_;
};

/// The unit vector along which the points spread most (power iteration on
/// their covariance); the x axis if they do not spread.
std::array<double, 3> principal_direction(const std::vector<std::array<double, 3>>& points);

}  // namespace ember::core
