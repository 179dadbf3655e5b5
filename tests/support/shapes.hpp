#pragma once
// Procedural test shapes (header-only). Every generator returns a closed mesh
// whose faces are counter-clockwise seen from outside (outward normals), with
// shared vertices, so each directed edge (a,b) has exactly one opposite (b,a).
//
// Also: rigid transforms, a seeded random rotation (own PRNG so results do not
// depend on the standard library's distributions), orientation reversal,
// merging meshes into one operand, and snapping onto a coarse dyadic grid.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <map>
#include <numbers>
#include <span>
#include <tuple>
#include <utility>
#include <vector>

#include "ember/mesh.hpp"

namespace ember::test {

// ---- small vector helpers ---------------------------------------------------
inline Vec3d operator+(Vec3d a, Vec3d b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
inline Vec3d operator-(Vec3d a, Vec3d b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
inline Vec3d operator*(double s, Vec3d a) { return {s * a.x, s * a.y, s * a.z}; }
inline double dot(Vec3d a, Vec3d b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
inline Vec3d cross(Vec3d a, Vec3d b) { return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x}; }
inline double norm(Vec3d a) { return std::sqrt(dot(a, a)); }

// ---- deterministic PRNG (splitmix64) ----------------------------------------
class Rng {
 public:
  explicit Rng(std::uint64_t seed) : s_(seed) {}
  std::uint64_t next() {
    std::uint64_t z = (s_ += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
  }
  /// Uniform in [0, 1).
  double uniform() { return static_cast<double>(next() >> 11) * 0x1.0p-53; }
  double uniform(double lo, double hi) { return lo + (hi - lo) * uniform(); }
  /// Uniform integer in [lo, hi].
  int integer(int lo, int hi) { return lo + static_cast<int>(next() % static_cast<std::uint64_t>(hi - lo + 1)); }

 private:
  std::uint64_t s_;
};

// ---- building blocks --------------------------------------------------------
/// Adds vertices with deduplication by exact coordinates (keeps meshes closed
/// when generators emit the same point more than once).
class MeshBuilder {
 public:
  std::uint32_t vertex(Vec3d p) {
    auto key = std::make_tuple(p.x, p.y, p.z);
    auto it = ids_.find(key);
    if (it != ids_.end()) return it->second;
    std::uint32_t id = mesh_.add_vertex(p);
    ids_.emplace(key, id);
    return id;
  }
  void face(std::initializer_list<Vec3d> pts) {
    std::vector<std::uint32_t> f;
    for (const Vec3d& p : pts) f.push_back(vertex(p));
    mesh_.add_face(f);
  }
  void face(std::span<const Vec3d> pts) {
    std::vector<std::uint32_t> f;
    for (const Vec3d& p : pts) f.push_back(vertex(p));
    mesh_.add_face(f);
  }
  Mesh take() { return std::move(mesh_); }

 private:
  Mesh mesh_;
  std::map<std::tuple<double, double, double>, std::uint32_t> ids_;
};

namespace detail {
/// Corner c of a box: bit 0 -> x, bit 1 -> y, bit 2 -> z (0 = min, 1 = max).
inline Vec3d corner(Vec3d lo, Vec3d hi, int c) {
  return {(c & 1) ? hi.x : lo.x, (c & 2) ? hi.y : lo.y, (c & 4) ? hi.z : lo.z};
}
/// The six faces of a box as corner indices, CCW from outside. Each quad is
/// listed starting at the corner with the smaller coordinates in the face plane
/// so that splitting along (q[0], q[2]) uses the diagonal from the min-min to
/// the max-max corner on every face: two boxes sharing a face then share the
/// same triangulation of it.
inline constexpr std::array<std::array<int, 4>, 6> kBoxQuads{{
    {0, 4, 6, 2},  // -x
    {1, 3, 7, 5},  // +x
    {0, 1, 5, 4},  // -y
    {2, 6, 7, 3},  // +y
    {0, 2, 3, 1},  // -z
    {4, 5, 7, 6},  // +z
}};
}  // namespace detail

/// Axis-aligned box as 12 triangles.
inline Mesh box(Vec3d lo, Vec3d hi) {
  Mesh m;
  for (int c = 0; c < 8; ++c) m.add_vertex(detail::corner(lo, hi, c));
  for (const auto& q : detail::kBoxQuads) {
    std::uint32_t a = q[0], b = q[1], c = q[2], d = q[3];
    m.add_face({a, b, c});
    m.add_face({a, c, d});
  }
  return m;
}

/// A coplanar pile: n unit cubes (12 triangles each), cube i shifted by
/// i * step along x. Every y and z face plane holds a stack of up to
/// 1 / step overlapping faces; the union is the box
/// [0, 1 + (n - 1) step] x [0, 1] x [0, 1].
inline std::vector<Mesh> shifted_cube_pile(int n, double step) {
  std::vector<Mesh> cubes;
  cubes.reserve(static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i) cubes.push_back(box({i * step, 0, 0}, {1 + i * step, 1, 1}));
  return cubes;
}

/// Axis-aligned box as 6 quads.
inline Mesh box_quads(Vec3d lo, Vec3d hi) {
  Mesh m;
  for (int c = 0; c < 8; ++c) m.add_vertex(detail::corner(lo, hi, c));
  for (const auto& q : detail::kBoxQuads)
    m.add_face({std::uint32_t(q[0]), std::uint32_t(q[1]), std::uint32_t(q[2]), std::uint32_t(q[3])});
  return m;
}

/// Axis-aligned box whose faces are split into a grid of `cells` x `cells`
/// quads each (many coplanar faces), triangulated if `triangles`.
inline Mesh tessellated_box(Vec3d lo, Vec3d hi, int cells, bool triangles = true) {
  MeshBuilder b;
  auto lerp = [&](double a, double c, int i) { return a + (c - a) * i / cells; };
  for (const auto& q : detail::kBoxQuads) {
    Vec3d p0 = detail::corner(lo, hi, q[0]), p1 = detail::corner(lo, hi, q[1]), p3 = detail::corner(lo, hi, q[3]);
    // Points on the face: p0 + s*(p1-p0) + t*(p3-p0); coordinates computed per
    // axis with lerp so that shared edges produce bitwise equal points.
    auto at = [&](int i, int j) {
      auto axis = [&](double a0, double a1, double a3) {
        if (a1 != a0) return lerp(a0, a1, i);
        if (a3 != a0) return lerp(a0, a3, j);
        return a0;
      };
      return Vec3d{axis(p0.x, p1.x, p3.x), axis(p0.y, p1.y, p3.y), axis(p0.z, p1.z, p3.z)};
    };
    for (int i = 0; i < cells; ++i)
      for (int j = 0; j < cells; ++j) {
        Vec3d a = at(i, j), c1 = at(i + 1, j), c2 = at(i + 1, j + 1), c3 = at(i, j + 1);
        if (triangles) {
          b.face({a, c1, c2});
          b.face({a, c2, c3});
        } else {
          b.face({a, c1, c2, c3});
        }
      }
  }
  return b.take();
}

/// Icosphere: an icosahedron subdivided `level` times, projected to the sphere.
inline Mesh icosphere(Vec3d center, double radius, int level) {
  const double t = (1.0 + std::sqrt(5.0)) / 2.0;
  std::vector<Vec3d> v{{-1, t, 0},  {1, t, 0},  {-1, -t, 0}, {1, -t, 0}, {0, -1, t},  {0, 1, t},
                       {0, -1, -t}, {0, 1, -t}, {t, 0, -1},  {t, 0, 1},  {-t, 0, -1}, {-t, 0, 1}};
  for (Vec3d& p : v) p = (1.0 / norm(p)) * p;
  std::vector<std::array<std::uint32_t, 3>> f{{0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11},
                                              {1, 5, 9},  {5, 11, 4}, {11, 10, 2}, {10, 7, 6}, {7, 1, 8},
                                              {3, 9, 4},  {3, 4, 2},  {3, 2, 6},   {3, 6, 8},  {3, 8, 9},
                                              {4, 9, 5},  {2, 4, 11}, {6, 2, 10},  {8, 6, 7},  {9, 8, 1}};
  for (int l = 0; l < level; ++l) {
    std::map<std::pair<std::uint32_t, std::uint32_t>, std::uint32_t> mid;
    auto midpoint = [&](std::uint32_t a, std::uint32_t b) {
      auto key = std::minmax(a, b);
      auto it = mid.find(key);
      if (it != mid.end()) return it->second;
      Vec3d m = 0.5 * (v[a] + v[b]);
      v.push_back((1.0 / norm(m)) * m);
      auto id = static_cast<std::uint32_t>(v.size() - 1);
      mid.emplace(key, id);
      return id;
    };
    std::vector<std::array<std::uint32_t, 3>> nf;
    for (auto [a, b, c] : f) {
      std::uint32_t ab = midpoint(a, b), bc = midpoint(b, c), ca = midpoint(c, a);
      nf.push_back({a, ab, ca});
      nf.push_back({b, bc, ab});
      nf.push_back({c, ca, bc});
      nf.push_back({ab, bc, ca});
    }
    f = std::move(nf);
  }
  Mesh m;
  for (const Vec3d& p : v) m.add_vertex(center + radius * p);
  for (auto [a, b, c] : f) m.add_face({a, b, c});
  return m;
}

/// UV sphere with `slices` around z and `stacks` from pole to pole; quads in
/// the middle, triangles at the poles.
inline Mesh uv_sphere(Vec3d center, double radius, int slices, int stacks) {
  Mesh m;
  const double pi = std::numbers::pi;
  std::uint32_t south = m.add_vertex(center + Vec3d{0, 0, -radius});
  for (int i = 1; i < stacks; ++i) {
    double phi = -pi / 2 + pi * i / stacks;
    for (int j = 0; j < slices; ++j) {
      double th = 2 * pi * j / slices;
      m.add_vertex(center + radius * Vec3d{std::cos(phi) * std::cos(th), std::cos(phi) * std::sin(th), std::sin(phi)});
    }
  }
  std::uint32_t north = m.add_vertex(center + Vec3d{0, 0, radius});
  auto ring = [&](int i, int j) { return static_cast<std::uint32_t>(1 + (i - 1) * slices + (j % slices)); };
  for (int j = 0; j < slices; ++j) m.add_face({south, ring(1, j + 1), ring(1, j)});
  for (int i = 1; i + 1 < stacks; ++i)
    for (int j = 0; j < slices; ++j) m.add_face({ring(i, j), ring(i, j + 1), ring(i + 1, j + 1), ring(i + 1, j)});
  for (int j = 0; j < slices; ++j) m.add_face({north, ring(stacks - 1, j), ring(stacks - 1, j + 1)});
  return m;
}

/// Torus around the z axis: major radius R, minor radius r, quads.
inline Mesh torus(Vec3d center, double R, double r, int major_segments, int minor_segments) {
  Mesh m;
  const double pi = std::numbers::pi;
  for (int i = 0; i < major_segments; ++i) {
    double u = 2 * pi * i / major_segments;
    for (int j = 0; j < minor_segments; ++j) {
      double v = 2 * pi * j / minor_segments;
      double rr = R + r * std::cos(v);
      m.add_vertex(center + Vec3d{rr * std::cos(u), rr * std::sin(u), r * std::sin(v)});
    }
  }
  auto id = [&](int i, int j) {
    return static_cast<std::uint32_t>((i % major_segments) * minor_segments + (j % minor_segments));
  };
  for (int i = 0; i < major_segments; ++i)
    for (int j = 0; j < minor_segments; ++j) m.add_face({id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1)});
  return m;
}

/// Cylinder along z from center.z to center.z + height; side quads, n-gon caps.
inline Mesh cylinder(Vec3d base_center, double radius, double height, int segments) {
  Mesh m;
  const double pi = std::numbers::pi;
  for (int k = 0; k < 2; ++k)
    for (int j = 0; j < segments; ++j) {
      double th = 2 * pi * j / segments;
      m.add_vertex(base_center + Vec3d{radius * std::cos(th), radius * std::sin(th), k * height});
    }
  auto id = [&](int k, int j) { return static_cast<std::uint32_t>(k * segments + (j % segments)); };
  for (int j = 0; j < segments; ++j) m.add_face({id(0, j), id(0, j + 1), id(1, j + 1), id(1, j)});
  std::vector<std::uint32_t> bottom, top;
  for (int j = segments - 1; j >= 0; --j) bottom.push_back(id(0, j));
  for (int j = 0; j < segments; ++j) top.push_back(id(1, j));
  m.add_face(bottom);
  m.add_face(top);
  return m;
}

/// Tetrahedron; the orientation is fixed so the result is outward whatever the
/// order of the points (a degenerate tetrahedron keeps the given order).
inline Mesh tetrahedron(Vec3d a, Vec3d b, Vec3d c, Vec3d d) {
  if (dot(cross(b - a, c - a), d - a) > 0) std::swap(b, c);
  Mesh m;
  m.add_vertex(a), m.add_vertex(b), m.add_vertex(c), m.add_vertex(d);
  m.add_face({0, 1, 2});
  m.add_face({0, 3, 1});
  m.add_face({1, 3, 2});
  m.add_face({2, 3, 0});
  return m;
}

// ---- transforms -------------------------------------------------------------
using Mat3 = std::array<std::array<double, 3>, 3>;

inline Vec3d apply(const Mat3& r, Vec3d p) {
  return {r[0][0] * p.x + r[0][1] * p.y + r[0][2] * p.z, r[1][0] * p.x + r[1][1] * p.y + r[1][2] * p.z,
          r[2][0] * p.x + r[2][1] * p.y + r[2][2] * p.z};
}

template <class F>
inline Mesh map_vertices(Mesh m, F&& f) {
  for (Vec3d& p : m.vertices) p = f(p);
  return m;
}
inline Mesh translate(Mesh m, Vec3d d) {
  return map_vertices(std::move(m), [&](Vec3d p) { return p + d; });
}
inline Mesh scale(Mesh m, double s) {
  return map_vertices(std::move(m), [&](Vec3d p) { return s * p; });
}
inline Mesh rotate(Mesh m, const Mat3& r) {
  return map_vertices(std::move(m), [&](Vec3d p) { return apply(r, p); });
}
inline Mat3 rotation_z(double angle) {
  double c = std::cos(angle), s = std::sin(angle);
  return Mat3{{{c, -s, 0}, {s, c, 0}, {0, 0, 1}}};
}
/// Uniformly distributed rotation (Shoemake's quaternion method), seeded.
inline Mat3 random_rotation(std::uint64_t seed) {
  Rng rng(seed);
  const double pi = std::numbers::pi;
  double u1 = rng.uniform(), u2 = rng.uniform(), u3 = rng.uniform();
  double a = std::sqrt(1 - u1), b = std::sqrt(u1);
  double w = a * std::sin(2 * pi * u2), x = a * std::cos(2 * pi * u2);
  double y = b * std::sin(2 * pi * u3), z = b * std::cos(2 * pi * u3);
  return Mat3{{{1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)},
               {2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)},
               {2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)}}};
}
inline Mesh reverse_orientation(Mesh m) {
  for (std::size_t f = 0; f < m.face_count(); ++f)
    std::reverse(m.indices.begin() + m.face_offsets[f], m.indices.begin() + m.face_offsets[f + 1]);
  return m;
}
/// All meshes as one operand (vertex indices shifted, no welding).
inline Mesh merge(std::span<const Mesh> parts) {
  Mesh out;
  for (const Mesh& p : parts) {
    auto base = static_cast<std::uint32_t>(out.vertices.size());
    out.vertices.insert(out.vertices.end(), p.vertices.begin(), p.vertices.end());
    for (std::size_t f = 0; f < p.face_count(); ++f) {
      std::vector<std::uint32_t> face;
      for (std::uint32_t i : p.face(f)) face.push_back(base + i);
      out.add_face(face);
    }
  }
  return out;
}
inline Mesh merge(std::initializer_list<Mesh> parts) {
  return merge(std::span<const Mesh>(parts.begin(), parts.size()));
}

/// Largest |coordinate| over all meshes.
inline double max_abs_coordinate(std::span<const Mesh> meshes) {
  double m = 0;
  for (const Mesh& mesh : meshes)
    for (const Vec3d& p : mesh.vertices) m = std::max({m, std::abs(p.x), std::abs(p.y), std::abs(p.z)});
  return m;
}

/// The grid step used by snap_to_grid for operands whose largest |coordinate|
/// is `max_abs`: 2^(ceil(log2 max_abs) - 21), i.e. every coordinate becomes an
/// integer multiple of the step with magnitude <= 2^21 steps. The library
/// quantizes all operands together with a power-of-two scale onto |q| <= 2^25;
/// even if its dyadic centre shifts the box by up to max_abs, its grid step is
/// at most 2^(ceil(log2 max_abs) - 23) = step / 4, and the centre is dyadic, so
/// snapped coordinates are represented exactly and "the volume of the quantized
/// inputs" equals the volume of the snapped meshes.
inline double snap_step(double max_abs) {
  int e = static_cast<int>(std::ceil(std::log2(max_abs > 0 ? max_abs : 1.0)));
  return std::ldexp(1.0, e - 21);
}
/// Rounds every coordinate of every mesh to a multiple of snap_step (in place).
inline void snap_to_grid(std::span<Mesh> meshes) {
  double h = snap_step(max_abs_coordinate(meshes));
  for (Mesh& m : meshes)
    for (Vec3d& p : m.vertices)
      p = {std::nearbyint(p.x / h) * h, std::nearbyint(p.y / h) * h, std::nearbyint(p.z / h) * h};
}
inline std::vector<Mesh> snapped(std::vector<Mesh> meshes) {
  snap_to_grid(meshes);
  return meshes;
}

// ---- paper configurations (Figs. 23-25) -------------------------------------
/// Fig. 24: N beams along x (operand 0, merged) and N beams along y (operand
/// 1). Beam i along x covers [-1, 2N] x [2i, 2i+1] x [0, 1]; beam j along y
/// covers [2j, 2j+1] x [-1, 2N] x [0, 1]. Their intersection is N^2 unit cubes
/// that all share the planes z = 0 and z = 1.
inline std::pair<Mesh, Mesh> beams(int n) {
  std::vector<Mesh> xs, ys;
  for (int i = 0; i < n; ++i) {
    xs.push_back(box({-1, 2.0 * i, 0}, {2.0 * n, 2.0 * i + 1, 1}));
    ys.push_back(box({2.0 * i, -1, 0}, {2.0 * i + 1, 2.0 * n, 1}));
  }
  return {merge(xs), merge(ys)};
}
/// Fig. 25, axis-aligned variant: n boxes [i, i+n] x [-i, n-i] x [0, 4], all
/// sharing the planes z = 0 and z = 4 (up to n coplanar faces on top of each
/// other). The intersection is [n-1, n] x [0, 1] x [0, 4].
inline std::vector<Mesh> staircase_cubes(int n) {
  std::vector<Mesh> out;
  for (int i = 0; i < n; ++i) out.push_back(box({double(i), double(-i), 0}, {double(i + n), double(n - i), 4}));
  return out;
}
/// Fig. 25 as in the paper: n squares of half-side a centred on the z axis,
/// rotated by k * (pi/2) / n, extruded over z in [0, 1]. The intersection is a
/// regular 4n-gon prism with inradius a.
inline std::vector<Mesh> rotated_cubes(int n, double a) {
  std::vector<Mesh> out;
  for (int k = 0; k < n; ++k)
    out.push_back(rotate(box({-a, -a, 0}, {a, a, 1}), rotation_z(k * std::numbers::pi / 2 / n)));
  return out;
}
/// A box inside a box, both outward, as one operand (winding number 2 inside
/// the inner box).
inline Mesh nested_shells(Vec3d outer_lo, Vec3d outer_hi, Vec3d inner_lo, Vec3d inner_hi) {
  return merge({box(outer_lo, outer_hi), box(inner_lo, inner_hi)});
}
/// Two overlapping boxes as one (self-intersecting) operand.
inline Mesh self_intersecting_pair(Vec3d lo0, Vec3d hi0, Vec3d lo1, Vec3d hi1) {
  return merge({box(lo0, hi0), box(lo1, hi1)});
}

}  // namespace ember::test
