#pragma once
// Independent reference measurements for Boolean results (header-only):
// signed volume, area, generalized winding numbers, point-to-surface distance,
// face sanity checks, a reference indicator with the paper's semantics (Eq. 5:
// "inside mesh i" means w_i != 0), a random point-membership check and exact
// voxel counting for unions of axis-aligned boxes.
#include <gmpxx.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <map>
#include <numbers>
#include <span>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "ember/boolean.hpp"
#include "ember/mesh.hpp"
#include "support/shapes.hpp"

namespace ember::test {

using ld = long double;

struct Vec3l {
  ld x = 0, y = 0, z = 0;
};
inline Vec3l to_l(Vec3d p) { return {p.x, p.y, p.z}; }
inline Vec3l operator-(Vec3l a, Vec3l b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
inline Vec3l operator+(Vec3l a, Vec3l b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
inline Vec3l operator*(ld s, Vec3l a) { return {s * a.x, s * a.y, s * a.z}; }
inline ld dot(Vec3l a, Vec3l b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
inline Vec3l cross(Vec3l a, Vec3l b) { return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x}; }
inline ld norm(Vec3l a) { return std::sqrt(dot(a, a)); }

/// Calls f(a, b, c) for every triangle of a fan triangulation of every face.
template <class F>
inline void for_each_fan_triangle(const Mesh& m, F&& f) {
  for (std::size_t i = 0; i < m.face_count(); ++i) {
    auto face = m.face(i);
    for (std::size_t k = 1; k + 1 < face.size(); ++k)
      f(m.vertices[face[0]], m.vertices[face[k]], m.vertices[face[k + 1]]);
  }
}

/// Six times the signed volume, accumulated in long double: exact for meshes
/// whose coordinates are small integers or dyadics (products stay below 2^64).
inline ld six_volume(const Mesh& m) {
  ld s = 0;
  for_each_fan_triangle(m, [&](Vec3d a, Vec3d b, Vec3d c) { s += dot(to_l(a), cross(to_l(b), to_l(c))); });
  return s;
}
/// Signed volume enclosed by the (closed up to T-junctions) surface.
inline double volume(const Mesh& m) { return static_cast<double>(six_volume(m) / 6); }
inline double volume(std::span<const Mesh> ms) {
  ld s = 0;
  for (const Mesh& m : ms) s += six_volume(m);
  return static_cast<double>(s / 6);
}

inline double surface_area(const Mesh& m) {
  ld s = 0;
  for_each_fan_triangle(m, [&](Vec3d a, Vec3d b, Vec3d c) { s += norm(cross(to_l(b) - to_l(a), to_l(c) - to_l(a))); });
  return static_cast<double>(s / 2);
}

/// Twice the vector area (sum of face area vectors); zero for a closed surface.
inline Vec3l twice_vector_area(const Mesh& m) {
  Vec3l s;
  for_each_fan_triangle(m, [&](Vec3d a, Vec3d b, Vec3d c) { s = s + cross(to_l(b) - to_l(a), to_l(c) - to_l(a)); });
  return s;
}

struct Bounds {
  Vec3d lo{std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity(),
           std::numeric_limits<double>::infinity()};
  Vec3d hi{-std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity(),
           -std::numeric_limits<double>::infinity()};
  void add(Vec3d p) {
    lo = {std::min(lo.x, p.x), std::min(lo.y, p.y), std::min(lo.z, p.z)};
    hi = {std::max(hi.x, p.x), std::max(hi.y, p.y), std::max(hi.z, p.z)};
  }
  void add(const Mesh& m) {
    for (const Vec3d& p : m.vertices) add(p);
  }
  bool valid() const { return lo.x <= hi.x; }
  double diagonal() const { return valid() ? norm(hi - lo) : 0.0; }
};

/// Generalized winding number of p (sum of signed solid angles / 4pi; Van
/// Oosterom-Strackee). An integer for closed surfaces, also with T-junctions.
inline double winding_number(const Mesh& m, Vec3d p) {
  ld total = 0;
  Vec3l q = to_l(p);
  for_each_fan_triangle(m, [&](Vec3d a0, Vec3d b0, Vec3d c0) {
    Vec3l a = to_l(a0) - q, b = to_l(b0) - q, c = to_l(c0) - q;
    ld la = norm(a), lb = norm(b), lc = norm(c);
    ld num = dot(a, cross(b, c));
    ld den = la * lb * lc + dot(a, b) * lc + dot(a, c) * lb + dot(b, c) * la;
    total += 2 * std::atan2(num, den);
  });
  return static_cast<double>(total / (4 * std::numbers::pi_v<ld>));
}

/// Distance from p to triangle abc (closest-point regions, Ericson 5.1.5).
inline double point_triangle_distance(Vec3d p, Vec3d a, Vec3d b, Vec3d c) {
  Vec3d ab = b - a, ac = c - a, ap = p - a;
  double d1 = dot(ab, ap), d2 = dot(ac, ap);
  if (d1 <= 0 && d2 <= 0) return norm(p - a);
  Vec3d bp = p - b;
  double d3 = dot(ab, bp), d4 = dot(ac, bp);
  if (d3 >= 0 && d4 <= d3) return norm(p - b);
  double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) return norm(p - (a + (d1 / (d1 - d3)) * ab));
  Vec3d cp = p - c;
  double d5 = dot(ab, cp), d6 = dot(ac, cp);
  if (d6 >= 0 && d5 <= d6) return norm(p - c);
  double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) return norm(p - (a + (d2 / (d2 - d6)) * ac));
  double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0)
    return norm(p - (b + ((d4 - d3) / ((d4 - d3) + (d5 - d6))) * (c - b)));
  double den = 1.0 / (va + vb + vc);
  double v = vb * den, w = vc * den;
  return norm(p - (a + v * ab + w * ac));
}

inline double distance_to_surface(const Mesh& m, Vec3d p) {
  double best = std::numeric_limits<double>::infinity();
  for_each_fan_triangle(m,
                        [&](Vec3d a, Vec3d b, Vec3d c) { best = std::min(best, point_triangle_distance(p, a, b, c)); });
  return best;
}

/// Structural problems of a result mesh: bad offsets or indices, faces with
/// fewer than 3 vertices, faces with zero area. With `convex_tol` >= 0 also
/// faces that are not convex or not planar beyond that tolerance (relative to
/// the face size); use 0 for exact (axis-aligned, integer) results. Returns ""
/// when there is nothing to report, else a description of the first problems.
inline std::string face_problems(const Mesh& m, double convex_tol = -1) {
  std::ostringstream out;
  int reported = 0;
  auto report = [&](std::size_t f, const std::string& what) {
    if (reported++ < 5) out << "face " << f << ": " << what << "; ";
  };
  if (m.face_offsets.empty() || m.face_offsets[0] != 0) return "face_offsets must start with 0";
  for (std::size_t f = 0; f + 1 < m.face_offsets.size(); ++f)
    if (m.face_offsets[f + 1] < m.face_offsets[f]) return "face_offsets not monotone";
  if (m.face_offsets.back() != m.indices.size()) return "face_offsets.back() != indices.size()";
  for (std::uint32_t i : m.indices)
    if (i >= m.vertices.size()) return "vertex index out of range";
  for (const Vec3d& p : m.vertices)
    if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z)) return "non-finite vertex";
  for (std::size_t f = 0; f < m.face_count(); ++f) {
    auto face = m.face(f);
    if (face.size() < 3) {
      report(f, "fewer than 3 vertices");
      continue;
    }
    // Twice the area vector, from differences to the first vertex so that
    // tiny slivers far from the origin do not cancel to zero.
    Vec3l n;
    ld size = 0;
    Vec3l o = to_l(m.vertices[face[0]]);
    for (std::size_t k = 0; k < face.size(); ++k) {
      Vec3l a = to_l(m.vertices[face[k]]), b = to_l(m.vertices[face[(k + 1) % face.size()]]);
      n = n + cross(a - o, b - o);
      size = std::max(size, norm(b - a));
    }
    ld nn = norm(n);
    if (!(nn > 0)) {
      std::ostringstream d;
      d.precision(17);
      d << "zero area:";
      for (std::uint32_t i : face)
        d << " (" << m.vertices[i].x << ", " << m.vertices[i].y << ", " << m.vertices[i].z << ")";
      report(f, d.str());
      continue;
    }
    if (convex_tol < 0) continue;
    Vec3l unit = (1 / nn) * n;
    for (std::size_t k = 0; k < face.size(); ++k) {
      Vec3l a = to_l(m.vertices[face[k]]), b = to_l(m.vertices[face[(k + 1) % face.size()]]),
            c = to_l(m.vertices[face[(k + 2) % face.size()]]);
      Vec3l t = cross(b - a, c - b);
      // Turning must be to the left of the normal (collinear allowed).
      if (dot(t, unit) < -convex_tol * size * size) {
        report(f, "not convex");
        break;
      }
      if (std::abs(dot(a - to_l(m.vertices[face[0]]), unit)) > convex_tol * size) {
        report(f, "not planar");
        break;
      }
    }
  }
  return reported ? out.str() : std::string();
}

/// True if every directed edge (a,b) is matched by exactly one (b,a) and no
/// directed edge repeats (generated shapes are closed, oriented 2-manifolds).
inline bool closed_oriented(const Mesh& m) {
  std::map<std::pair<std::uint32_t, std::uint32_t>, int> count;
  for (std::size_t f = 0; f < m.face_count(); ++f) {
    auto face = m.face(f);
    for (std::size_t k = 0; k < face.size(); ++k) ++count[{face[k], face[(k + 1) % face.size()]}];
  }
  for (const auto& [e, c] : count) {
    if (c != 1) return false;
    auto it = count.find({e.second, e.first});
    if (it == count.end() || it->second != 1) return false;
  }
  return true;
}

/// Undirected edges whose uses in the two directions differ in number: 0 means
/// closed and consistently oriented (non-manifold edges allowed when their uses
/// balance, as where solids touch along an edge).
/// Calls f(a, b) for every directed edge a -> b (a != b) of every face.
template <class F>
inline void for_each_directed_edge(const Mesh& m, F&& f) {
  for (std::size_t face_index = 0; face_index < m.face_count(); ++face_index) {
    auto face = m.face(face_index);
    for (std::size_t k = 0; k < face.size(); ++k)
      if (face[k] != face[(k + 1) % face.size()]) f(face[k], face[(k + 1) % face.size()]);
  }
}

inline std::size_t unbalanced_edges(const Mesh& m) {
  std::map<std::pair<std::uint32_t, std::uint32_t>, int> balance;
  for_each_directed_edge(m, [&](std::uint32_t a, std::uint32_t b) {
    balance[{std::min(a, b), std::max(a, b)}] += a < b ? 1 : -1;
  });
  std::size_t bad = 0;
  for (const auto& [e, c] : balance) bad += c != 0;
  return bad;
}

/// Vertices lying strictly inside an edge of a face (T-junctions), decided
/// exactly on the written doubles (rationals via GMP), counted over edges
/// whose undirected uses are exactly two: on a non-manifold line the sheets
/// are stitched separately by design (core/mesh/tjunctions.cpp).
inline std::size_t tjunction_vertices(const Mesh& m) {
  std::map<std::pair<std::uint32_t, std::uint32_t>, int> uses;
  for_each_directed_edge(m, [&](std::uint32_t a, std::uint32_t b) { ++uses[{std::min(a, b), std::max(a, b)}]; });
  std::vector<std::uint32_t> by_x(m.vertices.size());
  for (std::uint32_t v = 0; v < by_x.size(); ++v) by_x[v] = v;
  std::sort(by_x.begin(), by_x.end(),
            [&](std::uint32_t a, std::uint32_t b) { return m.vertices[a].x < m.vertices[b].x; });
  std::size_t found = 0;
  for (const auto& [e, count] : uses) {
    if (count != 2) continue;
    const Vec3d &a = m.vertices[e.first], &b = m.vertices[e.second];
    const double lo = std::min(a.x, b.x), hi = std::max(a.x, b.x);
    auto it =
        std::lower_bound(by_x.begin(), by_x.end(), lo, [&](std::uint32_t v, double x) { return m.vertices[v].x < x; });
    for (; it != by_x.end() && m.vertices[*it].x <= hi; ++it) {
      const Vec3d& p = m.vertices[*it];
      if (*it == e.first || *it == e.second || p.y < std::min(a.y, b.y) || p.y > std::max(a.y, b.y) ||
          p.z < std::min(a.z, b.z) || p.z > std::max(a.z, b.z))
        continue;
      const mpq_class d[3] = {mpq_class(b.x) - a.x, mpq_class(b.y) - a.y, mpq_class(b.z) - a.z};
      const mpq_class q[3] = {mpq_class(p.x) - a.x, mpq_class(p.y) - a.y, mpq_class(p.z) - a.z};
      if (d[1] * q[2] != d[2] * q[1] || d[2] * q[0] != d[0] * q[2] || d[0] * q[1] != d[1] * q[0]) continue;
      const mpq_class t = d[0] * q[0] + d[1] * q[1] + d[2] * q[2], len = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
      found += t > 0 && t < len;
    }
  }
  return found;
}

/// Reference indicators written independently of the library, with the paper's
/// semantics (Eq. 5): a point is inside operand i iff w_i != 0.
inline Indicator reference_indicator(Operation op, std::size_t n, int min_k = 1) {
  return [op, n, min_k](WindingVector w) {
    std::size_t inside = 0;
    for (std::size_t i = 0; i < n; ++i) inside += w[i] != 0;
    switch (op) {
      case Operation::Union: return inside >= 1;
      case Operation::Intersection: return inside == n;
      case Operation::Difference: return w[0] != 0 && inside == 1;
      case Operation::Xor: return inside % 2 == 1;
      case Operation::AtLeastK: return inside >= static_cast<std::size_t>(min_k);
    }
    return false;
  };
}

struct MembershipReport {
  int checked = 0;      ///< points compared
  int skipped = 0;      ///< points too close to a surface
  int mismatches = 0;   ///< output winding number != indicator of the inputs
  int non_integer = 0;  ///< winding numbers that were not close to an integer
  std::string first;    ///< description of the first mismatch
};

/// Samples random points in the joint bounding box of the operands (slightly
/// enlarged), skips points within rel_eps * diagonal of any input or output
/// surface, and compares the output's winding number (must be 1 inside, 0
/// outside) with the indicator applied to the operands' winding numbers.
/// Stops after `wanted` compared points or 40 * wanted tries.
inline MembershipReport membership_check(std::span<const Mesh> operands, const Indicator& indicator, const Mesh& output,
                                         int wanted, std::uint64_t seed, double rel_eps = 1e-5) {
  MembershipReport r;
  Bounds b;
  for (const Mesh& m : operands) b.add(m);
  if (!b.valid()) return r;
  double diag = b.diagonal();
  Vec3d pad{diag * 0.02, diag * 0.02, diag * 0.02};
  Vec3d lo = b.lo - pad, hi = b.hi + pad;
  double eps = rel_eps * diag;
  Rng rng(seed);
  std::vector<int> w(operands.size());
  for (int tries = 0; r.checked < wanted && tries < 40 * wanted; ++tries) {
    Vec3d p{rng.uniform(lo.x, hi.x), rng.uniform(lo.y, hi.y), rng.uniform(lo.z, hi.z)};
    bool near = distance_to_surface(output, p) < eps;
    for (std::size_t i = 0; i < operands.size() && !near; ++i) near = distance_to_surface(operands[i], p) < eps;
    if (near) {
      ++r.skipped;
      continue;
    }
    bool integral = true;
    for (std::size_t i = 0; i < operands.size(); ++i) {
      double wi = winding_number(operands[i], p);
      w[i] = static_cast<int>(std::lround(wi));
      integral = integral && std::abs(wi - w[i]) < 1e-3;
    }
    double wo = winding_number(output, p);
    long wo_r = std::lround(wo);
    integral = integral && std::abs(wo - wo_r) < 1e-3;
    if (!integral) ++r.non_integer;
    bool expected = indicator(WindingVector(w.data(), w.size()));
    ++r.checked;
    if (wo_r != (expected ? 1 : 0) || !integral) {
      if (r.mismatches++ == 0) {
        std::ostringstream s;
        s << "at (" << p.x << ", " << p.y << ", " << p.z << "): inputs w = (";
        for (std::size_t i = 0; i < w.size(); ++i) s << (i ? ", " : "") << w[i];
        s << ") -> expected " << (expected ? "inside" : "outside") << ", output winding number " << wo;
        r.first = s.str();
      }
    }
  }
  return r;
}
inline MembershipReport membership_check(std::span<const Mesh> operands, Operation op, const Mesh& output, int wanted,
                                         std::uint64_t seed, int min_k = 1, double rel_eps = 1e-5) {
  return membership_check(operands, reference_indicator(op, operands.size(), min_k), output, wanted, seed, rel_eps);
}

/// An axis-aligned box (for the voxel reference).
struct Box {
  Vec3d lo, hi;
};

/// Exact volume of {x : indicator(w(x))} where operand i is the union (with
/// multiplicity: winding number = number of containing boxes) of operands[i],
/// by counting cells of size `cell` (all box coordinates must be multiples of
/// `cell`; a power of two keeps the result exact).
inline double voxel_volume(const std::vector<std::vector<Box>>& operands, const Indicator& indicator,
                           double cell = 1.0) {
  Bounds b;
  for (const auto& op : operands)
    for (const Box& x : op) b.add(x.lo), b.add(x.hi);
  if (!b.valid()) return 0;
  auto cells = [&](double lo, double hi) { return static_cast<long>(std::lround((hi - lo) / cell)); };
  long nx = cells(b.lo.x, b.hi.x), ny = cells(b.lo.y, b.hi.y), nz = cells(b.lo.z, b.hi.z);
  std::vector<int> w(operands.size());
  long count = 0;
  for (long i = 0; i < nx; ++i)
    for (long j = 0; j < ny; ++j)
      for (long k = 0; k < nz; ++k) {
        Vec3d c{b.lo.x + (i + 0.5) * cell, b.lo.y + (j + 0.5) * cell, b.lo.z + (k + 0.5) * cell};
        for (std::size_t o = 0; o < operands.size(); ++o) {
          w[o] = 0;
          for (const Box& x : operands[o])
            w[o] += c.x > x.lo.x && c.x < x.hi.x && c.y > x.lo.y && c.y < x.hi.y && c.z > x.lo.z && c.z < x.hi.z;
        }
        count += indicator(WindingVector(w.data(), w.size()));
      }
  return static_cast<double>(count) * cell * cell * cell;
}

/// Meshes (12 triangles per box, merged per operand) for voxel_volume inputs.
inline std::vector<Mesh> box_meshes(const std::vector<std::vector<Box>>& operands) {
  std::vector<Mesh> out;
  for (const auto& op : operands) {
    std::vector<Mesh> parts;
    for (const Box& x : op) parts.push_back(box(x.lo, x.hi));
    out.push_back(merge(parts));
  }
  return out;
}

/// |a - b| <= rel * max(|a|, |b|, floor_abs).
inline bool close_rel(double a, double b, double rel, double floor_abs = 0) {
  return std::abs(a - b) <= rel * std::max({std::abs(a), std::abs(b), floor_abs});
}

}  // namespace ember::test
