// Piles that no subdivision plane separates : they must stay
// exact, and their leaves must not cut every polygon by every other one.
// Times are reported from the CLI (docs/design.md), not asserted here.
#include <gtest/gtest.h>

#include <cmath>
#include <optional>

#include "core/route/general/subdivide.hpp"
#include "support/boolean_checks.hpp"

namespace ember::test {
namespace {

/// Keeps the first run's mesh; every later run's must be the same, byte for byte.
void expect_same_as_first(std::optional<Mesh>& first, const Mesh& mesh, int threads) {
  if (!first) {
    first = mesh;
    return;
  }
  EXPECT_EQ(mesh.vertices, first->vertices) << threads << " threads";
  EXPECT_EQ(mesh.indices, first->indices) << threads << " threads";
  EXPECT_EQ(mesh.face_offsets, first->face_offsets) << threads << " threads";
}

/// A closed n-gon prism (radius 1, `length` long) along the diagonal
/// direction (1, 0.8, 0.6), its cross-section turned by `turn` and its base
/// moved by `shift` along the axis; caps fanned from their centres. Every
/// side triangle spans the whole rod, so its box meets every other side
/// triangle's.
Mesh diagonal_prism(int n, double length, double turn, double shift) {
  const double s = std::sqrt(1 + 0.64 + 0.36);
  const std::array<double, 3> d{1 / s, 0.8 / s, 0.6 / s};
  std::array<double, 3> u{d[1], -d[0], 0};  // orthogonal to d
  const double lu = std::hypot(u[0], u[1]);
  for (double& x : u) x /= lu;
  const std::array<double, 3> v{d[1] * u[2] - d[2] * u[1], d[2] * u[0] - d[0] * u[2], d[0] * u[1] - d[1] * u[0]};
  Mesh m;
  const auto point = [&](double angle, double along) {
    const double c = std::cos(angle), sn = std::sin(angle);
    return Vec3d{c * u[0] + sn * v[0] + along * d[0], c * u[1] + sn * v[1] + along * d[1],
                 c * u[2] + sn * v[2] + along * d[2]};
  };
  const auto id = [&](int i, int ring) { return static_cast<std::uint32_t>(2 * (i % n) + ring); };
  for (int i = 0; i < n; ++i) {
    const double a = turn + 2 * M_PI * i / n;
    m.vertices.push_back(point(a, shift));
    m.vertices.push_back(point(a, shift + length));
  }
  const auto centre = [&](double along) {
    m.vertices.push_back({along * d[0], along * d[1], along * d[2]});
    return static_cast<std::uint32_t>(m.vertices.size() - 1);
  };
  const std::uint32_t bottom = centre(shift), top = centre(shift + length);
  for (int i = 0; i < n; ++i) {
    // u x v = d: counter-clockwise around d, so (b_i, b_i+1, t_i+1) faces outward.
    m.add_face({id(i, 0), id(i + 1, 0), id(i + 1, 1)});
    m.add_face({id(i, 0), id(i + 1, 1), id(i, 1)});
    m.add_face({bottom, id(i + 1, 0), id(i, 0)});
    m.add_face({top, id(i, 1), id(i + 1, 1)});
  }
  return m;
}

/// Two solid rods of long side triangles crossing along their whole length:
/// each triangle's box meets hundreds of the other rod's, past the budget of
/// the partner search that starts alongside the proof
/// (kSpeculativePartnersPerTriangle). It gives up, and once the proof has
/// passed the solid path runs again: the same result at every thread count.
TEST(Piles, CrowdedSolidRodsTakeTheSolidPathAtEveryThreadCount) {
  const std::vector<Mesh> rods{diagonal_prism(1000, 100, 0, 0), diagonal_prism(1000, 100, M_PI / 1000, 0.5)};
  std::optional<Mesh> first;
  for (const int threads : {1, 2, 3}) {
    BooleanOptions opt;
    opt.threads = threads;
    const BooleanResult r = boolean(rods, Operation::Union, opt);
    EXPECT_EQ(r.stats.solid_operands, 2u);
    EXPECT_TRUE(r.stats.diagnostic("solid_path") != 0);
    EXPECT_TRUE(r.warnings.empty());
    expect_same_as_first(first, r.mesh, threads);
  }
  EXPECT_NEAR(volume(*first), 100.5 * 1000 * std::sin(2 * M_PI / 1000) / 2, 2.0);
}

/// The same kind of rods on the general path: their leaves are piles
/// (hundreds of side triangles each), where gather keeps only the polygons
/// that may share more than one point with t (the end fans' triangles share
/// one vertex with every side triangle that ends there). Without the solid
/// check every polygon of both rods is gathered; the result must be the
/// solid path's surface (run_checked also compares the solid path with the
/// subdivision on proven operands), watertight, the same at every thread
/// count.
TEST(Piles, GeneralPathRodsAgreeWithTheSolidPath) {
  const std::vector<Mesh> rods{diagonal_prism(200, 40, 0, 0), diagonal_prism(200, 40, M_PI / 200, 0.5)};
  const BooleanResult solid = run_checked(rods, Operation::Union);
  ASSERT_TRUE(solid.stats.diagnostic("solid_path") != 0);
  EXPECT_NEAR(volume(solid.mesh), 40.5 * 200 * std::sin(2 * M_PI / 200) / 2, 1.0);
  std::optional<Mesh> first;
  for (const int threads : {1, 2}) {
    BooleanOptions opt;
    opt.threads = threads;
    opt.detect_solid = false;
    const BooleanResult r = run_checked(rods, Operation::Union, opt);
    EXPECT_FALSE(r.stats.diagnostic("solid_path") != 0);
    EXPECT_TRUE(close_rel(volume(r.mesh), volume(solid.mesh), 1e-9, 1e-12)) << volume(r.mesh);
    EXPECT_TRUE(close_rel(surface_area(r.mesh), surface_area(solid.mesh), 1e-9, 1e-12)) << surface_area(r.mesh);
    expect_same_as_first(first, r.mesh, threads);
  }
}

/// The split rule: a split pays while (n + s)^2 < 2 n^2, s < 0.414 n.
TEST(Piles, SplitPaysWhileFewerThanSqrt2Minus1OfThePolygonsStraddle) {
  EXPECT_TRUE(core::split_pays(1000, 0));
  EXPECT_TRUE(core::split_pays(1000, 414));   // 1414^2 = 1,999,396 < 2,000,000
  EXPECT_FALSE(core::split_pays(1000, 415));  // 1415^2 = 2,002,225
  EXPECT_FALSE(core::split_pays(1000, 1000));
  EXPECT_TRUE(core::split_pays(70, 28));   // 98^2 = 9,604 < 9,800
  EXPECT_FALSE(core::split_pays(70, 29));  // 99^2 = 9,801
  // Sizes whose squares overflow 64 bits are compared exactly too.
  constexpr std::size_t kHuge = std::size_t{1} << 40;
  EXPECT_TRUE(core::split_pays(kHuge, kHuge / 1000 * 414));
  EXPECT_FALSE(core::split_pays(kHuge, kHuge / 1000 * 415));
  // 3/4 straddling (the old rule's limit) no longer splits.
  EXPECT_FALSE(core::split_pays(4000, 2999));
}

/// The union of unit cubes shifted by 1/128 along x (a dyadic step, so the
/// volume is exact): stacks of up to 128 coplanar faces in every y/z plane.
TEST(Piles, ShiftedCubeUnionIsOneBox) {
  constexpr int kCubes = 200;
  constexpr double kStep = 1.0 / 128;
  const std::vector<Mesh> cubes = shifted_cube_pile(kCubes, kStep);
  const double length = 1 + (kCubes - 1) * kStep;
  for (const int threads : {1, 2}) {
    BooleanOptions opt;
    opt.threads = threads;
    const BooleanResult r = run_checked(cubes, Operation::Union, opt, 0);
    EXPECT_EQ(r.stats.solid_operands, static_cast<std::size_t>(kCubes));
    EXPECT_DOUBLE_EQ(volume(r.mesh), length);
    EXPECT_DOUBLE_EQ(surface_area(r.mesh), 2 * (2 * length + 1));
    // The box's surface is emitted once: a few pieces per stacked polygon,
    // not the quadratic arrangement of all stacked edges (was 120k).
    EXPECT_LT(r.mesh.face_count(), std::size_t{20} * cubes.size() * 12);
  }
}

/// The general path (no solid knowledge) on the same stack: its pile leaf
/// (here all 2,400 polygons: every split leaves most of them in both
/// children, see split_pays) is shared by the threads in fixed blocks of 512
/// (leaf.cpp), so the result is the same at every thread count.
TEST(Piles, GeneralPathPileIsTheSameAtEveryThreadCount) {
  constexpr int kCubes = 200;
  constexpr double kStep = 1.0 / 128;
  const std::vector<Mesh> cubes = shifted_cube_pile(kCubes, kStep);
  std::optional<Mesh> first;
  for (const int threads : {1, 2, 4}) {
    BooleanOptions opt;
    opt.threads = threads;
    opt.detect_solid = false;
    const BooleanResult r = run_checked(cubes, Operation::Union, opt, 0);
    EXPECT_EQ(r.stats.solid_operands, 0u);
    EXPECT_DOUBLE_EQ(volume(r.mesh), 1 + (kCubes - 1) * kStep);
    expect_same_as_first(first, r.mesh, threads);
  }
}

/// The same stack with the 0.01 step of the issue (not dyadic: coordinates
/// round onto the grid), through every operation on a few cubes and the union
/// of all: the intersection is the overlap of the extreme cubes.
TEST(Piles, DecimalShiftedCubesAllOperations) {
  const std::vector<Mesh> cubes = shifted_cube_pile(200, 0.01);
  BooleanOptions opt;
  opt.threads = 2;
  const BooleanResult u = run_checked(cubes, Operation::Union, opt, 0);
  EXPECT_NEAR(volume(u.mesh), 2.99, 1e-6);
  const std::vector<Mesh> few(cubes.begin(), cubes.begin() + 40);
  EXPECT_NEAR(volume(run_checked(few, Operation::Intersection, opt, 0).mesh), 0.61, 1e-6);
  EXPECT_NEAR(volume(run_checked(
                         few, Operation::AtLeastK,
                         [] {
                           BooleanOptions o;
                           o.min_k = 20;
                           return o;
                         }(),
                         0)
                         .mesh),
              1.01, 1e-6);  // x in [0.19, 1.20]: inside at least 20 of the 40 cubes
  EXPECT_NEAR(volume(run_checked({cubes[0], cubes[50]}, Operation::Difference, opt, 0).mesh), 0.5, 1e-6);
  EXPECT_NEAR(volume(run_checked({cubes[0], cubes[50]}, Operation::Xor, opt, 0).mesh), 1.0, 1e-6);
}

}  // namespace
}  // namespace ember::test
