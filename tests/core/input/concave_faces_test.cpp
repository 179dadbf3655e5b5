// Exact triangulation of concave n-gons on the grid before the solid proof.
#include <string>

#include "support/boolean_checks.hpp"
#include "core/input/face_triangulation.hpp"
#include "core/input/quantize.hpp"

namespace ember::test {
namespace {

using Op = Operation;

/// An L-shaped prism whose two caps are concave hexagons (one face each).
Mesh l_prism() {
  Mesh m;
  const double xy[6][2] = {{0, 0}, {3, 0}, {3, 1}, {1, 1}, {1, 3}, {0, 3}};
  for (const double z : {0.0, 1.0})
    for (const auto& p : xy) m.add_vertex({p[0], p[1], z});
  m.add_face({5, 4, 3, 2, 1, 0});    // bottom, facing -z
  m.add_face({6, 7, 8, 9, 10, 11});  // top, facing +z
  for (std::uint32_t i = 0; i < 6; ++i) {
    const std::uint32_t j = (i + 1) % 6;
    m.add_face({i, j, j + 6, i + 6});
  }
  return m;
}

TEST(ConcaveFaces, LPrismWithHexagonCapsIsProvenSolidAndExact) {
  const Mesh l = l_prism();
  const BooleanResult r = run_checked({l, box({2, 0, 0}, {4, 1, 1})}, Op::Union);
  EXPECT_EQ(r.stats.operands[0].solid, SolidStatus::Proven) << describe_solid_check(r.stats.operands[0]);
  EXPECT_TRUE(r.warnings.empty()) << r.warnings[0];
  EXPECT_EQ(volume(r.mesh), 6.0);  // 5 + 2 - overlap 1
}

/// Twice the signed projected (xy) area of triangles over the corners.
std::int64_t twice_area(std::span<const IntPoint> c, const std::vector<std::array<std::uint32_t, 3>>& tris, bool& ccw) {
  std::int64_t sum = 0;
  ccw = true;
  for (const auto& t : tris) {
    const IntPoint &a = c[t[0]], &b = c[t[1]], &d = c[t[2]];
    const std::int64_t o = (b.x - a.x) * (d.y - a.y) - (b.y - a.y) * (d.x - a.x);
    ccw &= o > 0;
    sum += o;
  }
  return sum;
}

TEST(ConcaveFaces, EarClippingCoversTheFaceWithPositiveTriangles) {
  // A comb: concave at three corners; the fan from corner 0 would overlap.
  const std::vector<IntPoint> comb{{0, 0, 5}, {6, 0, 5}, {6, 4, 5}, {5, 4, 5}, {5, 1, 5}, {3, 1, 5},
                                   {3, 4, 5}, {2, 4, 5}, {2, 1, 5}, {1, 1, 5}, {1, 4, 5}, {0, 4, 5}};
  std::vector<std::array<std::uint32_t, 3>> tris;
  core::triangulate_polygon(comb, tris);
  ASSERT_EQ(tris.size(), comb.size() - 2);
  bool ccw = false;
  EXPECT_EQ(twice_area(comb, tris, ccw), 2 * (6 * 1 + 3 * 3));
  EXPECT_TRUE(ccw);
  // A figure eight has no area and no ear clipping: the fan is kept (it
  // gives the same winding numbers as the face).
  const std::vector<IntPoint> eight{{0, 0, 0}, {2, 2, 0}, {2, 0, 0}, {0, 2, 0}};
  tris.clear();
  core::triangulate_polygon(eight, tris);
  EXPECT_EQ(tris, (std::vector<std::array<std::uint32_t, 3>>{{0, 1, 2}, {0, 2, 3}}));
}

}  // namespace
}  // namespace ember::test
