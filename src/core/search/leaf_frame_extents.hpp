#pragma once
// The extents of the triangles in each leaf of a TriangleTree along the axes
// of a frame (leaf_extents.hpp), for the solid proof's contact search: an
// operand of long slivers along a direction off the axes (such as a pile of
// rods) has boxes and diagonal extents that overlap by the hundreds per
// triangle, which a frame along the slivers tells apart, leaving a small
// fraction of those pairs for the exact test.
#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <cstdint>
#include <limits>
#include <span>
#include <vector>

#include "core/search/leaf_extents.hpp"
#include "core/support/principal_frame.hpp"

namespace ember::core {

/// Bounds of the triangle's projections onto the frame's three axes, widened
/// past the rounding of their double evaluation, so that triangles with a
/// common point never have extents apart (any linear map keeps a common
/// point's image in both triangles' images, orthonormal or not).
/// Bits: |coordinate| <= 2^25 and |axis entry| <= 1 + 2^-52, so each product
/// is below 2^26 and rounds by at most 2^-28, each of the two sums (below
/// 2^27) by at most 2^-26: the evaluated projection is within 2^-24 of the
/// exact one. Truncation to an integer moves it by less than 1 and the bounds
/// add 2 more (cheaper than libm's floor and ceil). |projection| <= |p| <
/// 2^26 for a unit axis: the bounds fit int32.
/// Always inlined: the compiler's choice flips with unrelated changes to the
/// solid path, and as a call it would add its overhead to every triangle of
/// the frame samples and extents.
[[gnu::always_inline]] inline ProjectedExtent<3> frame_extent(const std::array<IntPoint, 3>& p,
                                                              const FrameAxes& frame) {
  static_assert(kCoordLimit <= (std::int64_t{1} << 25),
                "frame projections: error < 2^-24, |bounds| < 2^26 + 3 (int32)");
  ProjectedExtent<3> e;
  for (std::size_t a = 0; a < 3; ++a) {
    const std::array<double, 3>& u = frame[a];
    double lo = std::numeric_limits<double>::infinity(), hi = -lo;
    for (const IntPoint& q : p) {
      const double s =
          u[0] * static_cast<double>(q.x) + u[1] * static_cast<double>(q.y) + u[2] * static_cast<double>(q.z);
      lo = std::min(lo, s);
      hi = std::max(hi, s);
    }
    e.lo[a] = static_cast<std::int64_t>(lo) - 2;
    e.hi[a] = static_cast<std::int64_t>(hi) + 2;
  }
  return e;
}

class LeafFrameExtents : public LeafExtents<3> {
 public:
  /// Over a tree of contact triangles (item i: tris[i]), along `frame`'s axes
  /// (unit vectors).
  LeafFrameExtents(const TriangleTree& tree, std::span<const ContactTriangle> tris, const FrameAxes& frame) {
    fill(tree, [&](std::uint32_t item) { return frame_extent(tris[item].p(), frame); });
    fill_nodes(tree);
  }
  /// Over a tree of grid triangles (item i: corners[i]): an operand's, for
  /// the solid path's partner search (both operands in one frame).
  LeafFrameExtents(const TriangleTree& tree, std::span<const std::array<IntPoint, 3>> corners, const FrameAxes& frame) {
    fill(tree, [&](std::uint32_t item) { return frame_extent(corners[item], frame); });
    fill_nodes(tree);
  }

  /// Every triangle under tree node a is apart in the frame from every one
  /// under node b (their extents' hulls are apart along an axis): a node
  /// pair whose boxes overlap but whose slivers lie side by side across the
  /// frame (a rod of slivers) needs no visit to its leaves.
  bool nodes_apart(std::size_t a, std::size_t b) const { return nodes_apart(a, *this, b); }
  /// The same for node a of this tree and node b of another's, in the same
  /// frame (the partner search's two operands).
  bool nodes_apart(std::size_t a, const LeafFrameExtents& other, std::size_t b) const {
    const NodeExtent &x = node_[a], &y = other.node_[b];
    bool apart = false;
    for (std::size_t k = 0; k < 3; ++k) apart |= x.hi[k] < y.lo[k] || y.hi[k] < x.lo[k];
    return apart;
  }

 private:
  struct NodeExtent {
    std::array<std::int32_t, 3> lo, hi;
    void add(const NodeExtent& o) {
      for (std::size_t k = 0; k < 3; ++k) {
        lo[k] = std::min(lo[k], o.lo[k]);
        hi[k] = std::max(hi[k], o.hi[k]);
      }
    }
  };

  /// The hull of each node's extents, in the tree's heap order; a leaf
  /// without triangles gets an empty hull (apart from everything).
  void fill_nodes(const TriangleTree& tree) {
    const std::size_t first_leaf = tree.first_leaf();
    NodeExtent empty;
    empty.lo.fill(std::numeric_limits<std::int32_t>::max());
    empty.hi.fill(std::numeric_limits<std::int32_t>::min());
    node_.assign(2 * first_leaf + 1, empty);
    tbb::parallel_for(std::size_t{0}, first_leaf + 1, [&](std::size_t k) {
      const auto [begin, end] = tree.leaf_slots(first_leaf + k);
      for (std::size_t slot = begin; slot < end; ++slot) {
        const Extent e = extent(slot);
        NodeExtent one;
        for (std::size_t a = 0; a < 3; ++a) {
          one.lo[a] = static_cast<std::int32_t>(e.lo[a]);
          one.hi[a] = static_cast<std::int32_t>(e.hi[a]);
        }
        node_[first_leaf + k].add(one);
      }
    });
    for (std::size_t n = first_leaf; n-- > 0;) {
      node_[n] = node_[2 * n + 1];
      node_[n].add(node_[2 * n + 2]);
    }
  }

  std::vector<NodeExtent> node_;
};

}  // namespace ember::core
