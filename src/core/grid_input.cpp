// Operands onto the grid and the audit of the rounding (see grid_input.hpp).
#include "core/grid_input.hpp"

#include <cmath>
#include <cstdio>

#include "core/triangulate.hpp"
#include "ember/error.hpp"

namespace ember::core {

namespace {

using ld = long double;

std::array<ld, 3> cross(const Vec3d& a, const Vec3d& b, const Vec3d& c) {
  const ld ux = ld(b.x) - a.x, uy = ld(b.y) - a.y, uz = ld(b.z) - a.z;
  const ld vx = ld(c.x) - a.x, vy = ld(c.y) - a.y, vz = ld(c.z) - a.z;
  return {uy * vz - uz * vy, uz * vx - ux * vz, ux * vy - uy * vx};
}

/// The input triangle has area: its normal is not lost in the rounding of
/// the computation (|n| > 2^-40 |u||v|, so collinear corners that merely
/// print differently do not count as features).
bool has_area(const std::array<ld, 3>& n, const Vec3d& a, const Vec3d& b, const Vec3d& c) {
  const auto len2 = [](const Vec3d& p, const Vec3d& q) {
    const ld x = ld(q.x) - p.x, y = ld(q.y) - p.y, z = ld(q.z) - p.z;
    return x * x + y * y + z * z;
  };
  const ld n2 = n[0] * n[0] + n[1] * n[1] + n[2] * n[2];
  return n2 > std::ldexp(ld(1), -80) * len2(a, b) * len2(a, c);
}

std::string format_step(double step) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.3g", step);
  return buf;
}

}  // namespace

GridInput to_grid(std::span<const Mesh> operands, const Quantizer& q) {
  GridInput g;
  g.lo = {Quantizer::kLimit, Quantizer::kLimit, Quantizer::kLimit};
  g.hi = {-Quantizer::kLimit, -Quantizer::kLimit, -Quantizer::kLimit};
  std::vector<IntPoint> corners;
  std::vector<std::array<std::uint32_t, 3>> tris;
  for (std::size_t o = 0; o < operands.size(); ++o) {
    const Mesh& m = operands[o];
    g.operand_begin.push_back(g.triangles.size());
    std::vector<IntPoint> grid(m.vertices.size());
    std::vector<char> done(m.vertices.size(), 0);
    for (const std::uint32_t v : m.indices)
      if (!done[v]) {
        grid[v] = q.quantize(m.vertices[v]);
        done[v] = 1;
        const std::int64_t c[3] = {grid[v].x, grid[v].y, grid[v].z};
        for (int a = 0; a < 3; ++a) {
          g.lo[a] = std::min(g.lo[a], c[a]);
          g.hi[a] = std::max(g.hi[a], c[a]);
        }
      }
    for (std::size_t f = 0; f < m.face_count(); ++f) {
      const auto face = m.face(f);
      corners.clear();
      for (const std::uint32_t v : face) corners.push_back(grid[v]);
      tris.clear();
      triangulate_polygon(corners, tris);
      for (const auto& t : tris)
        g.triangles.push_back({{corners[t[0]], corners[t[1]], corners[t[2]]},
                               {face[t[0]], face[t[1]], face[t[2]]},
                               static_cast<std::uint32_t>(o),
                               static_cast<std::uint32_t>(f)});
    }
  }
  g.operand_begin.push_back(g.triangles.size());
  return g;
}

void audit_quantization(std::span<const Mesh> operands, const GridInput& grid, const Quantizer& q,
                        std::vector<OperandReport>& reports, std::vector<std::string>& warnings) {
  for (std::size_t o = 0; o < operands.size(); ++o) {
    OperandReport& r = reports[o];
    std::size_t with_area = 0;
    for (std::size_t i = grid.operand_begin[o]; i < grid.operand_begin[o + 1]; ++i) {
      const GridTriangle& t = grid.triangles[i];
      const Vec3d& a = operands[o].vertices[t.v[0]];
      const Vec3d& b = operands[o].vertices[t.v[1]];
      const Vec3d& c = operands[o].vertices[t.v[2]];
      const std::array<ld, 3> n = cross(a, b, c);
      if (!has_area(n, a, b, c)) continue;
      ++with_area;
      // Grid corners differ by < 2^26 per axis: the normal is exact in int64.
      const std::int64_t ux = t.p[1].x - t.p[0].x, uy = t.p[1].y - t.p[0].y, uz = t.p[1].z - t.p[0].z;
      const std::int64_t vx = t.p[2].x - t.p[0].x, vy = t.p[2].y - t.p[0].y, vz = t.p[2].z - t.p[0].z;
      const std::int64_t g[3] = {uy * vz - uz * vy, uz * vx - ux * vz, ux * vy - uy * vx};
      if (g[0] == 0 && g[1] == 0 && g[2] == 0)
        ++r.collapsed_triangles;
      else if (n[0] * g[0] + n[1] * g[1] + n[2] * g[2] < 0)
        ++r.flipped_triangles;
    }
    r.triangles = grid.operand_begin[o + 1] - grid.operand_begin[o];
    const std::size_t changed = r.collapsed_triangles + r.flipped_triangles;
    if (changed == 0) continue;
    const std::string what = std::to_string(r.collapsed_triangles) + " of its " + std::to_string(with_area) +
                             " triangles collapse and " + std::to_string(r.flipped_triangles) +
                             " flip on the quantization grid (step " + format_step(q.grid_spacing()) +
                             "; 2^26 steps span the bounding box of all operands together)";
    // Most of the operand gone or inverted: the result would not be the
    // Boolean of the given shapes, so refuse rather than answer wrongly.
    if (2 * changed > with_area)
      throw Error("operand " + std::to_string(o) + ": " + what +
                  "; most of the operand is lost on the grid, so the result would not be the Boolean of the given "
                  "shapes. It is thinner than the step or too small beside the other operands: remove far-away or "
                  "huge geometry, or scale the operands to similar sizes");
    warnings.push_back("operand " + std::to_string(o) + ": " + what + "; features finer than the step are lost");
  }
}

}  // namespace ember::core
