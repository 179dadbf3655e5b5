// Principal frames (src/core/principal_frame.hpp): the filters are sound in
// any frame, so what is checked here is that the frame is orthonormal and
// right-handed and finds the directions that make the filters effective:
// the line a rod of points runs along, and the normal of a flat pile.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "core/support/principal_frame.hpp"

namespace ember::test {
namespace {

using V3 = std::array<double, 3>;

double dot(const V3& a, const V3& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

void expect_orthonormal_right_handed(const core::FrameAxes& f) {
  for (int a = 0; a < 3; ++a)
    for (int b = 0; b < 3; ++b) EXPECT_NEAR(dot(f[a], f[b]), a == b ? 1.0 : 0.0, 1e-12) << a << ", " << b;
  const V3 c{f[0][1] * f[1][2] - f[0][2] * f[1][1], f[0][2] * f[1][0] - f[0][0] * f[1][2],
             f[0][0] * f[1][1] - f[0][1] * f[1][0]};
  EXPECT_NEAR(dot(c, f[2]), 1.0, 1e-12);
}

TEST(PrincipalFrame, FindsTheRodsLineAndTheFlatPilesNormal) {
  std::mt19937 rng(43);
  std::uniform_real_distribution<double> t(-1, 1);
  const double s = 1 / std::sqrt(3.0);
  const V3 d{s, -s, s};                                                     // a rod along a diagonal
  const V3 p{1 / std::sqrt(2.0), 1 / std::sqrt(2.0), 0};                    // orthogonal to d
  const V3 q{-1 / std::sqrt(6.0), 1 / std::sqrt(6.0), 2 / std::sqrt(6.0)};  // d x p
  std::vector<V3> points;
  for (int k = 0; k < 2000; ++k) {  // long along d, wider along p than along q
    const double a = 1000 * t(rng), b = 30 * t(rng), c = 3 * t(rng);
    points.push_back(
        {a * d[0] + b * p[0] + c * q[0] + 5e6, a * d[1] + b * p[1] + c * q[1], a * d[2] + b * p[2] + c * q[2]});
  }
  core::FrameAxes f;
  ASSERT_TRUE(core::principal_frame(points, f));
  expect_orthonormal_right_handed(f);
  EXPECT_GT(std::fabs(dot(f[0], d)), 0.9999);
  EXPECT_GT(std::fabs(dot(f[1], p)), 0.999);
  EXPECT_GT(std::fabs(dot(f[2], q)), 0.999) << "the pile's thin direction is the third axis";
}

TEST(PrincipalFrame, DegeneratePointSetsStillGetAFrame) {
  // All on one line: any frame around it; one point or none: a frame all
  // the same (the axes), never a failure or a NaN.
  std::vector<V3> line;
  for (int k = 0; k < 50; ++k) line.push_back({2.0 * k, 3.0 * k, -1.0 * k});
  core::FrameAxes f;
  ASSERT_TRUE(core::principal_frame(line, f));
  expect_orthonormal_right_handed(f);
  EXPECT_GT(std::fabs(dot(f[0], V3{2 / std::sqrt(14.0), 3 / std::sqrt(14.0), -1 / std::sqrt(14.0)})), 0.9999);
  for (const std::vector<V3>& few : {std::vector<V3>{}, std::vector<V3>{{1, 2, 3}}}) {
    ASSERT_TRUE(core::principal_frame(few, f));
    expect_orthonormal_right_handed(f);
  }
}

}  // namespace
}  // namespace ember::test
