#pragma once
// Whether a principal frame is worth its extents (leaf_frame_extents.hpp):
// a few triangles, evenly spaced, queried against a tree, count the box
// pairs that the diagonals keep and the frame dismisses. Shared by the
// proof's contact search (an operand against itself, sliver_frame) and the
// solid path's partner search (one operand against another, partner_frame).
// Only a cost decision: any frame is sound.
#include <tbb/blocked_range.h>
#include <tbb/parallel_reduce.h>

#include <algorithm>
#include <array>
#include <cstddef>
#include <vector>

#include "core/leaf_frame_extents.hpp"
#include "core/solid_check.hpp"
#include "core/triangle_tree.hpp"

namespace ember::core {

/// Where the sample's triangles lose at least this many box pairs per
/// triangle to the frame that the boxes and diagonals keep, the frame's
/// extents are worth building: ~200 instructions per triangle (the frame,
/// the extents, a mask per leaf pair) against ~60 per exact test saved.
inline constexpr double kFramePairsPerTriangle = 4;
/// Triangles sampled for that estimate (evenly spaced): one in 64, from 8
/// to 16. Each costs a tree query and its box pairs' extents, ~15k
/// instructions on the bunny pair and pair015 (the tree's upper nodes
/// overlap). The sliver operands dismiss hundreds of pairs per triangle:
/// any sample tells. (Comparing each sample only with its 32 neighbours on
/// either side in the tree's order instead cost as much and missed
/// pair018's operand.)
inline constexpr std::size_t kFrameSampleMin = 8, kFrameSampleMax = 16;
/// Corners the frame is computed from (evenly spaced): enough to find the
/// directions.
inline constexpr std::size_t kFrameCorners = 1024;

/// The first corners of about kFrameCorners of the n triangles corners(i),
/// evenly spaced, as doubles (the points principal_frame takes).
template <typename Corners>
std::vector<std::array<double, 3>> frame_points(std::size_t n, Corners&& corners) {
  std::vector<std::array<double, 3>> points;
  for (std::size_t i = 0; i < n; i += std::max<std::size_t>(1, n / kFrameCorners)) {
    const IntPoint& p = corners(i)[0];
    points.push_back({static_cast<double>(p.x), static_cast<double>(p.y), static_cast<double>(p.z)});
  }
  return points;
}

/// Per frame in `frames`, the box pairs that the diagonals keep and the
/// frame dismisses, between a sample of the nx triangles x(i) and the
/// triangles y(j) of `y_tree` (item j), summed over the sample; `sampled`
/// is the sample's size. `same`: x and y are one operand (a triangle is not
/// paired with itself).
/// The samples side by side (oneTBB): one can cost a few milliseconds where
/// it meets slivers by the hundreds (EMBER case 16's common frame), and the
/// combined broad phase waits for it (combined_search.cpp). Integer counts:
/// the sum does not depend on the split.
template <std::size_t F, typename XCorners, typename YCorners>
std::array<std::size_t, F> frame_dismissals(std::size_t nx, XCorners&& x, const TriangleTree& y_tree, YCorners&& y,
                                            const std::array<FrameAxes, F>& frames, bool same, std::size_t& sampled) {
  const std::size_t samples = std::clamp<std::size_t>(nx / 64, kFrameSampleMin, kFrameSampleMax);
  const std::size_t step = std::max<std::size_t>(1, nx / samples);
  sampled = (nx + step - 1) / step;
  using Counts = std::array<std::size_t, F>;
  return tbb::parallel_reduce(
      tbb::blocked_range<std::size_t>(0, sampled, 1), Counts{},
      [&](const tbb::blocked_range<std::size_t>& r, Counts dismissed) {
        for (std::size_t k = r.begin(); k != r.end(); ++k) {
          const std::size_t i = k * step;
          const std::array<IntPoint, 3>& p = x(i);
          const DiagonalExtent diagonal = diagonal_extent(p);
          std::array<ProjectedExtent<3>, F> along;
          for (std::size_t f = 0; f < F; ++f) along[f] = frame_extent(p, frames[f]);
          y_tree.for_each_overlapping(box_of(p), [&](std::uint32_t j) {
            const std::array<IntPoint, 3>& q = y(j);
            if ((same && j == i) || diagonally_apart(diagonal, diagonal_extent(q))) return;
            for (std::size_t f = 0; f < F; ++f) dismissed[f] += extents_apart(along[f], frame_extent(q, frames[f]));
          });
        }
        return dismissed;
      },
      [](Counts a, const Counts& b) {
        for (std::size_t f = 0; f < F; ++f) a[f] += b[f];
        return a;
      });
}

}  // namespace ember::core
