// Principal frames (see the header).
#include "core/support/principal_frame.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>

namespace ember::core {

namespace {

using V3 = std::array<double, 3>;

V3 cross(const V3& a, const V3& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}

bool normalize(V3& v) {
  const double n = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
  if (!(n > 0) || !std::isfinite(n)) return false;
  for (double& x : v) x /= n;
  return true;
}

/// The points' covariance (about their mean).
std::array<V3, 3> covariance(const std::vector<V3>& points) {
  V3 mean{};
  for (const V3& p : points)
    for (int a = 0; a < 3; ++a) mean[a] += p[a];
  for (double& m : mean) m /= static_cast<double>(std::max<std::size_t>(1, points.size()));
  std::array<V3, 3> cov{};
  for (const V3& p : points) {
    const V3 d{p[0] - mean[0], p[1] - mean[1], p[2] - mean[2]};
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c) cov[r][c] += d[r] * d[c];
  }
  return cov;
}

/// The unit vector along which the covariance is largest (power iteration),
/// among those orthogonal to `normal` where given; false where the points do
/// not spread (in that plane).
bool dominant(const std::array<V3, 3>& cov, const V3* normal, V3& v) {
  v = {1, 0.7548776662, 0.5698402910};  // not orthogonal to any axis-aligned eigenvector
  for (int it = 0; it < 64; ++it) {
    V3 next{};
    for (int r = 0; r < 3; ++r) next[r] = cov[r][0] * v[0] + cov[r][1] * v[1] + cov[r][2] * v[2];
    if (normal) {
      const double along = next[0] * (*normal)[0] + next[1] * (*normal)[1] + next[2] * (*normal)[2];
      for (int r = 0; r < 3; ++r) next[r] -= along * (*normal)[r];
    }
    if (!normalize(next)) return false;
    v = next;
  }
  return true;
}

}  // namespace

bool principal_frame(const std::vector<std::array<double, 3>>& points, FrameAxes& frame) {
  const std::array<V3, 3> cov = covariance(points);
  V3 e0, e1;
  if (!dominant(cov, nullptr, e0)) e0 = {1, 0, 0};
  if (!dominant(cov, &e0, e1)) return frame_along(e0, frame);
  // Where the points hardly spread across e0 (on a line), e1 came out of
  // rounding noise: any frame around e0 serves.
  const auto spread = [&](const V3& v) {
    double s = 0;
    for (int r = 0; r < 3; ++r) s += v[r] * (cov[r][0] * v[0] + cov[r][1] * v[1] + cov[r][2] * v[2]);
    return s;
  };
  if (!(spread(e1) > 1e-9 * spread(e0))) return frame_along(e0, frame);
  // Orthonormal to rounding: e2 across both, then e1 across e2 and e0.
  V3 e2 = cross(e0, e1);
  if (!normalize(e2)) return frame_along(e0, frame);
  e1 = cross(e2, e0);
  if (!normalize(e1)) return frame_along(e0, frame);
  frame = {e0, e1, e2};
  return true;
}

bool frame_along(const std::array<double, 3>& e0, FrameAxes& frame) {
  int least = 0;
  for (int k = 1; k < 3; ++k)
    if (std::fabs(e0[k]) < std::fabs(e0[least])) least = k;
  V3 axis{};
  axis[least] = 1;
  V3 e1 = cross(e0, axis);
  if (!normalize(e1)) return false;
  frame = {e0, e1, cross(e0, e1)};
  return true;
}

}  // namespace ember::core
