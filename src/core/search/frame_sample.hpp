#pragma once
// Whether a principal frame is worth its extents (leaf_frame_extents.hpp):
// a few triangles, evenly spaced, queried against a tree, count the box
// pairs that the diagonals keep and the frame dismisses. Shared by the
// proof's contact search (an operand against itself, sliver_frame) and the
// solid path's partner search (one operand against another, partner_frame).
// Only a cost decision: any frame is sound.
#include <algorithm>
#include <array>
#include <cstddef>
#include <vector>

#include "core/search/leaf_frame_extents.hpp"
#include "core/search/extents.hpp"
#include "core/search/triangle_tree.hpp"

namespace ember::core {

/// Where the sample's triangles lose at least this many box pairs per
/// triangle to the frame that the boxes and diagonals keep, the frame's
/// extents are worth building: ~200 instructions per triangle (the frame,
/// the extents, a mask per leaf pair) against ~60 per exact test saved.
inline constexpr double kFramePairsPerTriangle = 4;
/// Triangles sampled for that estimate (evenly spaced): one in 64, from 8
/// to 16. Each costs a tree query and its box pairs' extents, which is
/// small but not negligible (the tree's upper nodes overlap), hence the
/// cap. Sliver operands dismiss hundreds of pairs per triangle: any sample
/// tells. (Comparing each sample only with its 32 neighbours on either side
/// in the tree's order instead costs as much and can miss an operand that
/// the frame would help.)
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
template <std::size_t F, typename XCorners, typename YCorners>
std::array<std::size_t, F> frame_dismissals(std::size_t nx, XCorners&& x, const TriangleTree& y_tree, YCorners&& y,
                                            const std::array<FrameAxes, F>& frames, bool same, std::size_t& sampled) {
  std::array<std::size_t, F> dismissed{};
  sampled = 0;
  const std::size_t samples = std::clamp<std::size_t>(nx / 64, kFrameSampleMin, kFrameSampleMax);
  for (std::size_t i = 0; i < nx; i += std::max<std::size_t>(1, nx / samples), ++sampled) {
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
}

}  // namespace ember::core
