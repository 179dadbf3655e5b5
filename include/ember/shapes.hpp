#pragma once
// Procedural closed solids (outward-oriented, counter-clockwise faces): for
// the demo, benchmarks, tests and users who want a first result without files.
#include <cmath>
#include <cstdint>
#include <numbers>

#include "ember/mesh.hpp"

namespace ember::shapes {

/// UV sphere with single pole vertices: (stacks-1)*slices + 2 vertices,
/// 2*slices*(stacks-1) triangles.
inline Mesh uv_sphere(Vec3d c, double radius, int slices, int stacks) {
  Mesh m;
  const double pi = std::numbers::pi;
  const std::uint32_t north = m.add_vertex({c.x, c.y, c.z + radius});
  for (int i = 1; i < stacks; ++i)
    for (int j = 0; j < slices; ++j) {
      const double th = pi * i / stacks, ph = 2 * pi * j / slices;
      m.add_vertex({c.x + radius * std::sin(th) * std::cos(ph), c.y + radius * std::sin(th) * std::sin(ph),
                    c.z + radius * std::cos(th)});
    }
  const std::uint32_t south = m.add_vertex({c.x, c.y, c.z - radius});
  auto id = [&](int i, int j) { return static_cast<std::uint32_t>(1 + (i - 1) * slices + (j % slices)); };
  for (int j = 0; j < slices; ++j) m.add_face({north, id(1, j), id(1, j + 1)});
  for (int i = 1; i + 1 < stacks; ++i)
    for (int j = 0; j < slices; ++j) {
      m.add_face({id(i, j), id(i + 1, j), id(i + 1, j + 1)});
      m.add_face({id(i, j), id(i + 1, j + 1), id(i, j + 1)});
    }
  for (int j = 0; j < slices; ++j) m.add_face({south, id(stacks - 1, j + 1), id(stacks - 1, j)});
  return m;
}

/// Torus around the z axis through the origin.
inline Mesh torus(double major, double minor, int seg_u, int seg_v) {
  Mesh m;
  const double tau = 2 * std::numbers::pi;
  for (int i = 0; i < seg_u; ++i)
    for (int j = 0; j < seg_v; ++j) {
      const double u = tau * i / seg_u, v = tau * j / seg_v;
      const double r = major + minor * std::cos(v);
      m.add_vertex({r * std::cos(u), r * std::sin(u), minor * std::sin(v)});
    }
  auto id = [&](int i, int j) { return static_cast<std::uint32_t>((i % seg_u) * seg_v + (j % seg_v)); };
  for (int i = 0; i < seg_u; ++i)
    for (int j = 0; j < seg_v; ++j) {
      m.add_face({id(i, j), id(i + 1, j), id(i + 1, j + 1)});
      m.add_face({id(i, j), id(i + 1, j + 1), id(i, j + 1)});
    }
  return m;
}

}  // namespace ember::shapes
