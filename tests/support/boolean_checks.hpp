#pragma once
// Helpers shared by the core tests: run a Boolean and check the invariants
// every result must satisfy (valid convex faces, provenance per face, stats).
#include <gtest/gtest.h>

#include <chrono>
#include <span>
#include <string>
#include <vector>

#include "ember/boolean.hpp"
#include "ember/csg.hpp"
#include "ember/error.hpp"
#include "support/mesh_checks.hpp"
#include "support/shapes.hpp"

namespace ember::test {

/// The default output is a triangle mesh that is closed and consistently
/// oriented whenever every operand is: every edge balanced, no
/// fallback regions, no vertex inside a (manifold) edge.
inline void expect_watertight_if_closed(std::span<const Mesh> ops, const BooleanOptions& opt, const BooleanResult& r) {
  if (opt.output != BooleanOptions::Output::Triangles) return;
  for (std::size_t f = 0; f < r.mesh.face_count(); ++f) ASSERT_EQ(r.mesh.face_size(f), 3u) << "face " << f;
  EXPECT_EQ(r.stats.diagnostic("fallback_regions"), 0u);
  for (const Mesh& m : ops)
    if (unbalanced_edges(m) != 0) return;
  EXPECT_EQ(unbalanced_edges(r.mesh), 0u) << "closed operands must give a closed, consistently oriented result";
  if (r.mesh.vertices.size() <= 20000) {
    EXPECT_EQ(tjunction_vertices(r.mesh), 0u) << "a vertex lies inside an edge of the output";
  }
}

/// The message of the ember::Error thrown by f ("" if none was thrown).
template <class F>
std::string error_message(F&& f) {
  try {
    f();
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

/// Runs the Boolean and checks the structural invariants of the result:
/// faces have >= 3 vertices, non-zero area and (with convex_tol >= 0) are
/// convex and planar; one provenance entry per face with indices in range;
/// stats.output_polygons matches.
/// `Rule` is an Operation or a Csg expression.
template <class Rule>
BooleanResult run_checked(std::span<const Mesh> ops, const Rule& op, const BooleanOptions& opt = {},
                          double convex_tol = -1) {
  BooleanResult r = boolean(ops, op, opt);
  EXPECT_EQ(face_problems(r.mesh, convex_tol), "");
  EXPECT_EQ(r.provenance.size(), r.mesh.face_count());
  for (const Provenance& p : r.provenance) {
    EXPECT_LT(p.operand, ops.size());
    if (p.operand < ops.size()) {
      EXPECT_LT(p.face, ops[p.operand].face_count());
    }
  }
  EXPECT_EQ(r.stats.output_polygons, r.mesh.face_count());
  expect_watertight_if_closed(ops, opt, r);
  // All operands solid: the solid path solved it; the subdivision must give
  // the same surface (its coplanar regions may be triangulated otherwise).
  if (r.stats.diagnostic("solid_path") != 0) {
    BooleanOptions subdivided = opt;
    subdivided.route = BooleanOptions::Route::General;
    const BooleanResult s = boolean(ops, op, subdivided);
    EXPECT_FALSE(s.stats.diagnostic("solid_path") != 0);
    EXPECT_TRUE(close_rel(volume(r.mesh), volume(s.mesh), 1e-9, 1e-12))
        << "the solid path changed the volume: " << volume(r.mesh) << " vs subdivided " << volume(s.mesh);
    EXPECT_TRUE(close_rel(surface_area(r.mesh), surface_area(s.mesh), 1e-9, 1e-12))
        << "the solid path changed the area: " << surface_area(r.mesh) << " vs subdivided " << surface_area(s.mesh);
  }
  // Operands proven solid take the shortcuts; the general path must agree.
  if (opt.detect_solid && r.stats.solid_operands > 0) {
    BooleanOptions general = opt;
    general.detect_solid = false;
    general.all_solid = false;
    general.solid.clear();
    const BooleanResult g = boolean(ops, op, general);
    if (g.stats.solid_operands != r.stats.solid_operands) {
      EXPECT_TRUE(close_rel(volume(r.mesh), volume(g.mesh), 1e-9, 1e-12))
          << "solid proof changed the volume: " << volume(r.mesh) << " vs general " << volume(g.mesh);
      EXPECT_TRUE(close_rel(surface_area(r.mesh), surface_area(g.mesh), 1e-9, 1e-12))
          << "solid proof changed the area: " << surface_area(r.mesh) << " vs general " << surface_area(g.mesh);
    }
  }
  return r;
}
inline BooleanResult run_checked(std::initializer_list<Mesh> ops, Operation op, const BooleanOptions& opt = {},
                                 double convex_tol = -1) {
  return run_checked(std::span<const Mesh>(ops.begin(), ops.size()), op, opt, convex_tol);
}

/// Four overlapping curved solids (sphere, torus, box, cylinder), snapped so
/// that volume identities hold exactly (shapes.hpp: snapped).
inline std::vector<Mesh> four_solids() {
  return snapped({icosphere({0, 0, 0}, 1.0, 3), rotate(torus({0.4, 0.1, 0.0}, 0.9, 0.3, 40, 16), random_rotation(5)),
                  translate(rotate(box({-0.6, -0.6, -0.6}, {0.6, 0.6, 0.6}), random_rotation(9)), {0.5, 0.3, 0.2}),
                  cylinder({-0.2, 0.1, -1.2}, 0.45, 2.4, 32)});
}

/// Options for the general path: no promise and no proof, so no operand is
/// solid and the subdivision with its early terminations solves it.
inline BooleanOptions general_path() {
  BooleanOptions o;
  o.detect_solid = false;
  return o;
}

/// Options with a custom indicator.
inline BooleanOptions with_indicator(Indicator f) {
  BooleanOptions o;
  o.indicator = std::move(f);
  return o;
}
inline BooleanOptions with_min_k(int k) {
  BooleanOptions o;
  o.min_k = k;
  return o;
}

/// For inputs with exact (small integer / dyadic) coordinates: every output
/// polygon lies exactly in the supporting plane of the input face named by its
/// provenance, and its normal is parallel to that face's normal (same or
/// opposite direction). Returns the number of violating polygons.
inline int provenance_plane_violations(std::span<const Mesh> ops, const BooleanResult& r) {
  int bad = 0;
  for (std::size_t f = 0; f < r.mesh.face_count() && f < r.provenance.size(); ++f) {
    const Provenance& pv = r.provenance[f];
    if (pv.operand >= ops.size() || pv.face >= ops[pv.operand].face_count()) {
      ++bad;
      continue;
    }
    const Mesh& src = ops[pv.operand];
    auto sf = src.face(pv.face);
    Vec3l p0 = to_l(src.vertices[sf[0]]);
    Vec3l n = cross(to_l(src.vertices[sf[1]]) - p0, to_l(src.vertices[sf[2]]) - p0);
    bool ok = true;
    auto of = r.mesh.face(f);
    for (std::uint32_t i : of) ok = ok && dot(n, to_l(r.mesh.vertices[i]) - p0) == 0;
    Vec3l on;
    for (std::size_t k = 0; k < of.size(); ++k)
      on = on + cross(to_l(r.mesh.vertices[of[k]]), to_l(r.mesh.vertices[of[(k + 1) % of.size()]]));
    Vec3l c = cross(n, on);
    ok = ok && c.x == 0 && c.y == 0 && c.z == 0;
    bad += !ok;
  }
  return bad;
}

/// Milliseconds since `t0`.
inline double ms_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

}  // namespace ember::test
