// Embedded vertex stars (src/core/vertex_stars.hpp): the certificate that
// lets the contact search skip neighbouring pairs must hold on ordinary
// closed meshes, fail on folded, non-manifold and doubly wound stars, and
// never hide a contact: with it, every count equals the exact all-pairs
// count without it.
#include <gtest/gtest.h>

#include <tbb/task_arena.h>

#include <cmath>
#include <numbers>
#include <random>

#include "support/contact_fixtures.hpp"
#include "core/proof/contact_search.hpp"
#include "core/proof/vertex_stars.hpp"
#include "support/shapes.hpp"

namespace ember::test {
namespace {

/// A mesh's faces (fanned) on the integer grid: coordinates times `scale`,
/// rounded.
std::vector<Tri> on_grid(const Mesh& m, double scale) {
  const auto grid = [&](std::uint32_t v) {
    const Vec3d& p = m.vertices[v];
    return IntPoint{std::llround(p.x * scale), std::llround(p.y * scale), std::llround(p.z * scale)};
  };
  std::vector<Tri> out;
  for (std::size_t f = 0; f < m.face_count(); ++f) {
    const auto face = m.face(f);
    for (std::size_t i = 1; i + 1 < face.size(); ++i) out.push_back({grid(face[0]), grid(face[i]), grid(face[i + 1])});
  }
  return out;
}

std::size_t certified_corners(const std::vector<core::ContactTriangle>& tris) {
  std::size_t n = 0;
  for (const core::ContactTriangle& t : tris) n += std::popcount(t.embedded);
  return n;
}

/// Certifies `tris` (neighbours by edge matching) and returns them.
std::vector<core::ContactTriangle> certified(std::vector<core::ContactTriangle> tris) {
  core::certify_embedded_stars(tris, manifold_neighbours(tris));
  return tris;
}

TEST(VertexStars, OrdinaryClosedMeshesAreCertifiedEverywhere) {
  for (const Mesh& m : {icosphere({0, 0, 0}, 1.0, 3), uv_sphere({0.1, 0, 0}, 1.0, 48, 20),
                        torus({0, 0, 0}, 1.0, 0.3, 32, 12), tessellated_box({0, 0, 0}, {1, 1, 1}, 3)}) {
    const std::vector<Tri> corners = on_grid(m, 1 << 20);
    const std::vector<core::ContactTriangle> tris = certified(with_ids(corners));
    EXPECT_EQ(certified_corners(tris), 3 * tris.size());  // cube corners and sphere poles included
  }
}

/// Triangles (v, w_i, w_{i+1}) around v = origin, with w_i at angle `turn` * i
/// in the plane z = 0 and radius 1000 + 100 i (distinct points): a fan that
/// closes after `spokes` spokes (w_spokes = w_0) and winds spokes * turn / 360
/// times.
std::vector<Tri> fan(int spokes, double turn) {
  std::vector<IntPoint> w;
  for (int i = 0; i < spokes; ++i) {
    const double a = turn * i * std::numbers::pi / 180, r = 1000.0 + 100.0 * i;
    w.push_back({std::llround(r * std::cos(a)), std::llround(r * std::sin(a)), 0});
  }
  std::vector<Tri> tris;
  for (int i = 0; i < spokes; ++i) tris.push_back({IntPoint{0, 0, 0}, w[i], w[(i + 1) % spokes]});
  return tris;
}

TEST(VertexStars, AFanWindingTwiceIsNotCertifiedAndItsOverlapIsFound) {
  // Six spokes 120 degrees apart: two turns. Triangles 0 and 3 cover the
  // same sector: coplanar, overlapping beyond v.
  const std::vector<Tri> fan6_120 = fan(6, 120), fan5_144 = fan(5, 144), fan6_60 = fan(6, 60), fan5_72 = fan(5, 72);
  const std::vector<core::ContactTriangle> twice = certified(with_ids(fan6_120));
  EXPECT_EQ(twice[0].embedded & 1, 0);
  EXPECT_TRUE(core::triangles_meet_improperly(twice[0], twice[3]));
  EXPECT_EQ(core::find_contacts(twice, 1000).pairs, all_pairs_count(twice));
  EXPECT_GT(all_pairs_count(twice), 0u);
  // Five spokes 144 degrees apart: two turns, no spoke parallel to another.
  const std::vector<core::ContactTriangle> five = certified(with_ids(fan5_144));
  EXPECT_EQ(five[0].embedded & 1, 0);
  EXPECT_EQ(core::find_contacts(five, 1000).pairs, all_pairs_count(five));
  EXPECT_GT(all_pairs_count(five), 0u);
  // The same fans winding once are certified at v (the only closed star
  // here), with a spoke at 180 degrees from the first one.
  const std::vector<core::ContactTriangle> once = certified(with_ids(fan6_60));
  EXPECT_EQ(once[0].embedded & 1, 1);
  EXPECT_EQ(all_pairs_count(once), 0u);
  EXPECT_EQ(certified(with_ids(fan5_72))[0].embedded & 1, 1);
}

TEST(VertexStars, TheCertificateHoldsAtTheGridsFullRange) {
  // The bit budget (d . n, d . (e_0 x e) in __int128, e_0 x e in int64)
  // at coordinates up to the grid's limit: closed meshes spanning +-(2^25 -
  // 1) are certified everywhere, and fans around a far corner, scaled to
  // spokes of ~2^24 (coordinates up to ~2^25), keep their verdicts.
  constexpr double kScale = static_cast<double>(kCoordLimit - 1);
  for (const Mesh& m : {icosphere({0, 0, 0}, 1.0, 3), tessellated_box({-1, -1, -1}, {1, 1, 1}, 3)}) {
    const std::vector<Tri> corners = on_grid(m, kScale);
    EXPECT_EQ(certified_corners(certified(with_ids(corners))), 3 * corners.size());
  }
  const auto far_fan = [](int spokes, double turn) {
    std::vector<Tri> tris = fan(spokes, turn);
    for (Tri& t : tris)
      for (IntPoint& p : t) p = IntPoint{p.x * 10000 - kCoordLimit / 2, p.y * 10000 + kCoordLimit / 2, p.z};
    return tris;
  };
  const std::vector<Tri> twice = far_fan(6, 120), once = far_fan(6, 60);
  EXPECT_EQ(certified(with_ids(twice))[0].embedded & 1, 0);
  EXPECT_EQ(certified(with_ids(once))[0].embedded & 1, 1);
}

TEST(VertexStars, FoldedAndNonManifoldStarsAreNotCertified) {
  // A fan winding once, but with spoke w_3 moved back to 100 degrees, before
  // w_2 (120): triangle (v, w_2, w_3) turns clockwise and folds over its
  // neighbours.
  std::vector<Tri> folded = fan(6, 60);
  folded[2][2] = {-226, 1280, 0};
  folded[3][1] = folded[2][2];
  EXPECT_EQ(certified(with_ids(folded))[0].embedded & 1, 0);
  // Two closed fans touching at v (a bow tie of two cones): not one cycle.
  std::vector<Tri> bow = fan(5, 72);
  for (Tri t : fan(4, 90)) {
    for (IntPoint& p : t) p.z = p == IntPoint{0, 0, 0} ? 0 : 700;  // a second, lifted fan
    bow.push_back(t);
  }
  EXPECT_EQ(certified(with_ids(bow))[0].embedded & 1, 0);
  // A closed fan plus a flap (v, a, w_0) on one of its spokes, listed first:
  // the walk from the flap goes once around the fan and never comes back.
  std::vector<Tri> flap{{IntPoint{0, 0, 0}, IntPoint{800, -800, 0}, fan(4, 90)[0][1]}};
  for (const Tri& t : fan(4, 90)) flap.push_back(t);
  const std::vector<core::ContactTriangle> flapped = certified(with_ids(flap));
  EXPECT_EQ(flapped[0].embedded & 1, 0);
  EXPECT_GT(all_pairs_count(flapped), 0u);  // the flap lies on the fan
}

/// A closed mesh with every vertex moved by up to `jitter` grid units
/// (seeded): large jitter folds stars and makes the surface cross itself.
std::vector<Tri> jittered(const Mesh& m, double scale, std::int64_t jitter, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_int_distribution<std::int64_t> d(-jitter, jitter);
  Mesh moved = m;
  std::vector<Vec3d> offset(m.vertices.size());
  for (Vec3d& o : offset) o = {static_cast<double>(d(rng)), static_cast<double>(d(rng)), static_cast<double>(d(rng))};
  for (std::size_t v = 0; v < m.vertices.size(); ++v) moved.vertices[v] = m.vertices[v] + (1.0 / scale) * offset[v];
  std::vector<Tri> tris;
  for (const Tri& t : on_grid(moved, scale)) {
    const std::array<std::int64_t, 3> n = grid_normal(t[0], t[1], t[2]);
    if (n != std::array<std::int64_t, 3>{0, 0, 0}) tris.push_back(t);
  }
  return tris;
}

TEST(VertexStars, CertificatesNeverHideAContact) {
  // The oracle: every pair tested exactly without any certificate. With the
  // certificates, the all-pairs count and the search must find as many.
  std::size_t certified_total = 0, uncertified_total = 0, contacts_total = 0;
  unsigned seed = 1;
  for (const Mesh& m : {icosphere({0, 0, 0}, 1.0, 2), torus({0, 0, 0}, 1.0, 0.35, 16, 8)}) {
    for (const std::int64_t jitter : {0, 20, 60, 150}) {
      const std::vector<Tri> corners = jittered(m, 400, jitter, seed++);
      const std::vector<core::ContactTriangle> plain = with_ids(corners);
      const std::size_t expected = all_pairs_count(plain);
      const std::vector<core::ContactTriangle> tris = certified(plain);
      EXPECT_EQ(all_pairs_count(tris), expected) << "jitter " << jitter;
      for (const int threads : {1, 2}) {
        tbb::task_arena arena(threads);
        core::ContactSearchResult r;
        arena.execute([&] { r = core::find_contacts(tris, 1u << 30); });
        EXPECT_EQ(r.pairs, expected) << "jitter " << jitter << ", " << threads << " threads";
      }
      certified_total += certified_corners(tris);
      uncertified_total += 3 * tris.size() - certified_corners(tris);
      contacts_total += expected;
    }
  }
  // Not vacuous: both kinds of star, and surfaces that do cross themselves.
  EXPECT_GT(certified_total, 1000u);
  EXPECT_GT(uncertified_total, 100u);
  EXPECT_GT(contacts_total, 10u);
}

TEST(VertexStars, CertifiedTrianglesStillMeetTheirNonNeighbours) {
  // Two clean spheres, one operand: every star is certified, so the search
  // skips every neighbour pair, yet the spheres cross each other and every
  // crossing pair must still be found.
  std::vector<Tri> tris = on_grid(icosphere({0, 0, 0}, 1.0, 3), 4000);
  const std::vector<Tri> other = on_grid(icosphere({0.6, 0.3, 0.2}, 0.8, 3), 4000);
  tris.insert(tris.end(), other.begin(), other.end());
  const std::vector<core::ContactTriangle> plain = with_ids(tris);
  const std::vector<core::ContactTriangle> certs = certified(plain);
  ASSERT_EQ(certified_corners(certs), 3 * certs.size());
  const std::size_t expected = all_pairs_count(plain);
  EXPECT_GT(expected, 50u);
  EXPECT_EQ(core::find_contacts(certs, 1u << 30).pairs, expected);
}

}  // namespace
}  // namespace ember::test
