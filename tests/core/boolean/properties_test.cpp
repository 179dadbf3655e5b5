// Properties (UVs, normals, colours) through Booleans, against exact
// references: a property that is a linear function of position must come out
// equal to that function at every output corner (linear interpolation of a
// linear function is exact), per-corner seams must stay seams while the mesh
// stays closed, and normals must follow the faces the Boolean reverses.
#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <set>

#include "support/boolean_checks.hpp"

namespace ember::test {
namespace {

using Op = Operation;

double field(const Vec3d& p) { return 0.25 * p.x - 0.5 * p.y + 0.125 * p.z + 1.0; }

/// A per-vertex property "f" = field(position).
Mesh with_field(Mesh m) {
  MeshProperty f{"f", 1, false, {}};
  for (const Vec3d& p : m.vertices) f.values.push_back(static_cast<float>(field(p)));
  m.properties.push_back(f);
  return m;
}

const MeshProperty& property(const Mesh& m, const std::string& name) {
  for (const MeshProperty& p : m.properties)
    if (p.name == name) return p;
  throw std::runtime_error("no property " + name);
}

TEST(Properties, ALinearFieldIsReproducedAtEveryOutputCorner) {
  const std::vector<Mesh> ops{with_field(box({-1, -1, -1}, {1, 1, 1})),
                              with_field(rotate(icosphere({0.3, 0.2, 0.1}, 1.1, 3), random_rotation(3)))};
  for (Op op : {Op::Union, Op::Intersection, Op::Difference, Op::Xor})
    for (const BooleanOptions& options : {BooleanOptions{}, general_path()}) {
      const BooleanResult r = run_checked(ops, op, options);
      const MeshProperty& f = property(r.mesh, "f");
      ASSERT_TRUE(f.per_corner);
      ASSERT_EQ(f.values.size(), r.mesh.indices.size());
      double worst = 0;
      for (std::size_t i = 0; i < r.mesh.indices.size(); ++i)
        worst = std::max(worst, std::abs(f.values[i] - field(r.mesh.vertices[r.mesh.indices[i]])));
      EXPECT_LT(worst, 1e-6) << "op " << int(op);  // float32 values of magnitude ~1
      EXPECT_TRUE(r.warnings.empty() || r.warnings.front().find("property") == std::string::npos);
    }
}

/// A cube whose every face has its own UV chart: per corner, uv = the two
/// coordinates of the face's plane (a seam along every edge).
Mesh charted_cube() {
  Mesh m = box({0, 0, 0}, {2, 2, 2});
  MeshProperty uv{"uv", 2, true, {}};
  for (std::size_t f = 0; f < m.face_count(); ++f) {
    const auto face = m.face(f);
    const Vec3d a = m.vertices[face[0]], b = m.vertices[face[1]], c = m.vertices[face[2]];
    const Vec3d n = cross(b - a, c - a);
    const int axis = std::abs(n.x) > 0.5 ? 0 : (std::abs(n.y) > 0.5 ? 1 : 2);
    for (const std::uint32_t v : face) {
      const Vec3d p = m.vertices[v];
      const double q[3] = {p.x, p.y, p.z};
      uv.values.push_back(static_cast<float>(q[(axis + 1) % 3]));
      uv.values.push_back(static_cast<float>(q[(axis + 2) % 3]));
    }
  }
  m.properties.push_back(uv);
  return m;
}

TEST(Properties, ATexturedCubeMinusASphereKeepsItsSeamsAndStaysClosed) {
  const std::vector<Mesh> ops{charted_cube(), uv_sphere({2, 2, 2}, 0.9, 32, 16)};
  const BooleanResult r = run_checked(ops, Op::Difference);
  EXPECT_EQ(unbalanced_edges(r.mesh), 0u);
  const MeshProperty& uv = property(r.mesh, "uv");
  // On the cube's faces each corner's uv is its face chart's projection.
  std::size_t seam_corners = 0;
  std::map<std::uint32_t, std::set<std::pair<float, float>>> uv_at_vertex;
  for (std::size_t f = 0; f < r.mesh.face_count(); ++f) {
    if (r.provenance[f].operand != 0) continue;
    const auto face = r.mesh.face(f);
    const Vec3d n =
        cross(r.mesh.vertices[face[1]] - r.mesh.vertices[face[0]], r.mesh.vertices[face[2]] - r.mesh.vertices[face[0]]);
    const int axis =
        std::abs(n.x) > std::abs(n.y) && std::abs(n.x) > std::abs(n.z) ? 0 : (std::abs(n.y) > std::abs(n.z) ? 1 : 2);
    for (std::size_t k = 0; k < face.size(); ++k) {
      const Vec3d p = r.mesh.vertices[face[k]];
      const double q[3] = {p.x, p.y, p.z};
      const std::size_t at = r.mesh.face_offsets[f] + k;
      EXPECT_NEAR(uv.values[2 * at], q[(axis + 1) % 3], 1e-6);
      EXPECT_NEAR(uv.values[2 * at + 1], q[(axis + 2) % 3], 1e-6);
      uv_at_vertex[face[k]].insert({uv.values[2 * at], uv.values[2 * at + 1]});
    }
  }
  for (const auto& [v, uvs] : uv_at_vertex) seam_corners += uvs.size() > 1;
  EXPECT_GT(seam_corners, 0u) << "the cube's edges must keep different uvs on their two faces";
  // The sphere has no uv: its faces get zeros, with a warning that says so.
  bool warned = false;
  for (const std::string& w : r.warnings) warned |= w.find("operand 1: has no property 'uv'") != std::string::npos;
  EXPECT_TRUE(warned);
}

TEST(Properties, NormalsTurnWithReversedFacesAndMissingOnesAreTheFacesOwn) {
  Mesh sphere = icosphere({0, 0, 0}, 1.0, 3);
  MeshProperty n{"normal", 3, false, {}};
  for (const Vec3d& p : sphere.vertices) {
    const double l = norm(p);
    n.values.insert(n.values.end(), {float(p.x / l), float(p.y / l), float(p.z / l)});
  }
  sphere.properties.push_back(n);
  const std::vector<Mesh> ops{box({-0.5, -0.5, -0.5}, {1.5, 1.5, 1.5}), sphere};
  const BooleanResult r = run_checked(ops, Op::Difference);  // the box minus the sphere
  const MeshProperty& normal = property(r.mesh, "normal");
  for (std::size_t f = 0; f < r.mesh.face_count(); ++f) {
    const auto face = r.mesh.face(f);
    const Vec3d geo =
        cross(r.mesh.vertices[face[1]] - r.mesh.vertices[face[0]], r.mesh.vertices[face[2]] - r.mesh.vertices[face[0]]);
    for (std::size_t k = 0; k < face.size(); ++k) {
      const std::size_t at = r.mesh.face_offsets[f] + k;
      const Vec3d v{normal.values[3 * at], normal.values[3 * at + 1], normal.values[3 * at + 2]};
      EXPECT_NEAR(norm(v), 1.0, 1e-5);
      // Every normal points out of the result: along the face's own orientation.
      EXPECT_GT(dot(v, geo), 0) << "face " << f << " from operand " << r.provenance[f].operand;
      if (r.provenance[f].operand == 1)  // the cavity's faces look towards the sphere's centre
        EXPECT_LT(dot(v, r.mesh.vertices[face[k]]), 0);
    }
  }
}

TEST(Properties, PropertiesOfTheWrongSizeOrWidthAreErrorsNamingTheOperand) {
  Mesh a = box({0, 0, 0}, {1, 1, 1});
  a.properties.push_back({"uv", 2, true, std::vector<float>(5, 0.0f)});
  EXPECT_NE(error_message([&] {
              boolean({box({0.5, 0.5, 0.5}, {2, 2, 2}), a}, Op::Union);
            }).find("operand 1: property 'uv' has 5 values; 36 corners of width 2 need 72"),
            std::string::npos);
  Mesh b = box({0, 0, 0}, {1, 1, 1}), c = box({0.5, 0.5, 0.5}, {2, 2, 2});
  b.properties.push_back({"uv", 2, false, std::vector<float>(16, 0.0f)});
  c.properties.push_back({"uv", 3, false, std::vector<float>(24, 0.0f)});
  EXPECT_NE(error_message([&] {
              boolean({b, c}, Op::Union);
            }).find("operand 1: property 'uv' has width 3"),
            std::string::npos);
}

}  // namespace
}  // namespace ember::test
