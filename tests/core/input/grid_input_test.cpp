// The quantization audit's per-triangle verdict (core/grid_input.hpp):
// rounding_change decides most triangles in double and must always give the
// long double definition's answer (rounding_change_reference), including
// near its area threshold, near n . g = 0, and at extreme scales where the
// double filter has to step aside. And the weld of the grid vertices: ids
// are the ranks of the distinct grid positions in (x, y, z) order.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdint>
#include <map>
#include <random>
#include <tuple>

#include "core/input/grid_input.hpp"

namespace ember::core {
namespace {

using Normal = std::array<std::int64_t, 3>;

std::array<double, 3> cross(const Vec3d& a, const Vec3d& b, const Vec3d& c) {
  const double ux = b.x - a.x, uy = b.y - a.y, uz = b.z - a.z;
  const double vx = c.x - a.x, vy = c.y - a.y, vz = c.z - a.z;
  return {uy * vz - uz * vy, uz * vx - ux * vz, ux * vy - uy * vx};
}

/// An integer vector of magnitude about 2^bits (bits <= 52) along d; along
/// (1, 0, 0) where d is zero or not finite (a normal that overflowed).
Normal along(const std::array<double, 3>& d, int bits) {
  const double m = std::max({std::fabs(d[0]), std::fabs(d[1]), std::fabs(d[2])});
  if (!(m > 0) || !std::isfinite(d[0]) || !std::isfinite(d[1]) || !std::isfinite(d[2]))
    return {std::int64_t{1} << bits, 0, 0};
  // d_i / m is in [-1, 1]: the components stay within 2^bits, no overflow.
  return {std::llround(std::ldexp(d[0] / m, bits)), std::llround(std::ldexp(d[1] / m, bits)),
          std::llround(std::ldexp(d[2] / m, bits))};
}

struct Tally {
  int checked = 0, failed = 0;
  int verdicts[4] = {0, 0, 0, 0};  // -1, 0, 1, 2
};

void check(const Vec3d& a, const Vec3d& b, const Vec3d& c, const Normal& g, Tally& t) {
  const int want = rounding_change_reference(a, b, c, g);
  const int got = rounding_change(a, b, c, g);
  ++t.checked;
  ++t.verdicts[want + 1];
  if (got != want && t.failed++ < 5)
    ADD_FAILURE() << "a=(" << a.x << "," << a.y << "," << a.z << ") b=(" << b.x << "," << b.y << "," << b.z << ") c=("
                  << c.x << "," << c.y << "," << c.z << ") g=(" << g[0] << "," << g[1] << "," << g[2] << "): got "
                  << got << ", want " << want;
}

TEST(RoundingChange, AgreesWithTheLongDoubleDefinition) {
  std::mt19937_64 rng(17);
  std::uniform_real_distribution<double> unit(-1, 1);
  std::uniform_int_distribution<int> scale(-1000, 1000), bits(0, 52);
  Tally t;
  for (int i = 0; i < 200000; ++i) {
    const int k = i % 4 == 0 ? scale(rng) : scale(rng) / 8;  // most near 1, a quarter anywhere in range
    const auto p = [&] { return Vec3d{std::ldexp(unit(rng), k), std::ldexp(unit(rng), k), std::ldexp(unit(rng), k)}; };
    Vec3d a = p(), b = p(), c = p();
    switch (i % 5) {
      case 1: {  // nearly collinear: c on the line ab, pushed off by ~2^-40 of the edge (the area threshold)
        const double s = unit(rng), off = std::ldexp(unit(rng), -40 + (i % 7) - 3);
        c = {a.x + s * (b.x - a.x) + off * (b.y - a.y), a.y + s * (b.y - a.y) - off * (b.x - a.x),
             a.z + s * (b.z - a.z)};
        break;
      }
      case 2:  // two corners equal, or all three
        c = i % 10 == 2 ? a : b;
        if (i % 20 == 2) b = a;
        break;
      default: break;
    }
    const std::array<double, 3> n = cross(a, b, c);
    Normal g;
    switch (i % 4) {
      case 0:  // along the normal or against it
        g = along(n, bits(rng));
        if (i % 8 == 0) g = {-g[0], -g[1], -g[2]};
        break;
      case 1: {  // nearly perpendicular to it: the sign of n . g is decided by the last bits
        const std::array<double, 3> w{unit(rng), unit(rng), unit(rng)};
        g = along({n[1] * w[2] - n[2] * w[1], n[2] * w[0] - n[0] * w[2], n[0] * w[1] - n[1] * w[0]}, 50);
        break;
      }
      case 2: g = {0, 0, 0}; break;
      default: {
        std::uniform_int_distribution<std::int64_t> any(-(std::int64_t{1} << 52), std::int64_t{1} << 52);
        g = {any(rng), any(rng), any(rng)};
        break;
      }
    }
    check(a, b, c, g, t);
  }
  EXPECT_EQ(t.failed, 0);
  // Every verdict occurs, so the comparison covered each branch.
  for (const int v : t.verdicts) EXPECT_GT(v, 1000);
}

TEST(RoundingChange, ExtremeScalesFallBackToTheDefinition) {
  Tally t;
  const Normal up{0, 0, 1}, down{0, 0, -1};
  for (const double s : {0x1p-1074, 0x1p-1022, 0x1p-600, 0x1p-201, 0x1p-199, 0x1p199, 0x1p201, 0x1p600, 0x1p1000}) {
    const Vec3d a{0, 0, 0}, b{s, 0, 0}, c{0, s, 0};
    check(a, b, c, up, t);
    check(a, b, c, down, t);
    check(a, b, Vec3d{s, s, 0}, up, t);                      // collinear
    check(a, Vec3d{s, 0, 0}, Vec3d{0, 0x1p-200, 0}, up, t);  // edges of very different lengths
  }
  EXPECT_EQ(t.failed, 0);
}

TEST(GridWeld, IdsAreTheRanksOfTheDistinctPositions) {
  // Operand 0: few distinct x (runs of equal x longer than the parallel
  // run sort's threshold), repeated positions under different indices, and
  // unused vertices; operand 1: spread out, runs of one.
  std::mt19937_64 rng(41);
  std::vector<Mesh> operands(2);
  for (int o = 0; o < 2; ++o) {
    Mesh& m = operands[static_cast<std::size_t>(o)];
    const int n = o == 0 ? 30000 : 8000;
    for (int i = 0; i < n; ++i) {
      if (o == 0 && i > 0 && rng() % 4 == 0) {  // a repeat of an earlier position
        m.add_vertex(m.vertices[rng() % m.vertices.size()]);
        continue;
      }
      const auto at = [&](int range) {
        return static_cast<double>(static_cast<int>(rng() % static_cast<unsigned>(range)));
      };
      m.add_vertex(o == 0 ? Vec3d{at(3), at(60), at(40)} : Vec3d{at(1000000), at(1000000), at(1000000)});
    }
    for (int f = 0; f < n; ++f) {  // some vertices stay unused
      const std::array<std::uint32_t, 3> face{static_cast<std::uint32_t>(rng() % static_cast<unsigned>(n - 50)),
                                              static_cast<std::uint32_t>(rng() % static_cast<unsigned>(n - 50)),
                                              static_cast<std::uint32_t>(rng() % static_cast<unsigned>(n - 50))};
      m.add_face(face);
    }
  }
  const UsedVertices used = used_vertices(operands);
  const Quantizer q = fit_used_vertices(operands, used);
  const GridInput gi = to_grid(operands, q, used);
  for (std::size_t o = 0; o < 2; ++o) {
    // The oracle: every used position's rank among the distinct ones.
    std::map<std::tuple<std::int64_t, std::int64_t, std::int64_t>, std::uint32_t> rank;
    for (const std::uint32_t v : used[o]) {
      const IntPoint p = q.quantize(operands[o].vertices[v]);
      rank[{p.x, p.y, p.z}] = 0;
    }
    std::uint32_t next = 0;
    for (auto& [position, r] : rank) r = next++;
    ASSERT_EQ(gi.vertex_count[o], rank.size()) << "operand " << o;
    if (o == 0) {
      EXPECT_LT(rank.size(), used[o].size()) << "operand 0 repeats positions";
    }
    for (std::size_t t = gi.operand_begin[o]; t < gi.operand_begin[o + 1]; ++t)
      for (int k = 0; k < 3; ++k) {
        const IntPoint p = q.quantize(operands[o].vertices[gi.triangles[t].v[static_cast<std::size_t>(k)]]);
        ASSERT_EQ(gi.vertex_ids[t][static_cast<std::size_t>(k)], rank.at({p.x, p.y, p.z})) << "triangle " << t;
      }
  }
}

}  // namespace
}  // namespace ember::core
