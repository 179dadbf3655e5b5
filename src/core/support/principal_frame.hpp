#pragma once
// Orthonormal frames along the direction in which a point set spreads most,
// for the filters that separate piles of long slivers: boxes in such a frame
// are thin across the slivers, where axis-aligned boxes of diagonal slivers
// all overlap (frame_boxes.hpp, mesh/vertex_index.hpp). Any frame is sound
// for them (their error bounds take the frame as an exact linear map with
// entries of magnitude at most 1); this one only makes them effective.
#include <array>
#include <vector>

namespace ember::core {

using FrameAxes = std::array<std::array<double, 3>, 3>;

/// The points' principal axes (power iteration on their covariance) as a
/// right-handed frame: the direction in which they spread most (the x axis if
/// they do not spread), then the most among those orthogonal to it
/// (where the points spread in only one direction, frame_along it); false
/// only where no frame could be formed. A pile of slivers along a plane is
/// thin along the third axis, which an arbitrary frame around the first
/// misses.
bool principal_frame(const std::vector<std::array<double, 3>>& points, FrameAxes& frame);

/// A right-handed orthonormal frame whose first axis is e0 (a unit vector);
/// false where e0 is not one.
bool frame_along(const std::array<double, 3>& e0, FrameAxes& frame);

}  // namespace ember::core
