// Principal frames (see the header).
#include "core/principal_frame.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>

namespace ember::core {

namespace {

using V3 = std::array<double, 3>;

V3 cross(const V3& a, const V3& b) { return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]}; }

bool normalize(V3& v) {
  const double n = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
  if (!(n > 0) || !std::isfinite(n)) return false;
  for (double& x : v) x /= n;
  return true;
}

}  // namespace

std::array<double, 3> principal_direction(const std::vector<std::array<double, 3>>& points) {
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
  V3 v{1, 0.7548776662, 0.5698402910};  // not orthogonal to any axis-aligned eigenvector
  for (int it = 0; it < 64; ++it) {
    V3 next{};
    for (int r = 0; r < 3; ++r) next[r] = cov[r][0] * v[0] + cov[r][1] * v[1] + cov[r][2] * v[2];
    if (!normalize(next)) return {1, 0, 0};
    v = next;
  }
  return v;
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
