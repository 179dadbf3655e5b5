// Face groups (Mesh::face_groups, e.g. materials) through Booleans: every
// output face takes its source face's group, named groups join by name, and
// coplanar faces of different groups are never merged into one region.
#include <gtest/gtest.h>

#include "support/boolean_checks.hpp"

namespace ember::test {
namespace {

using Op = Operation;

Mesh grouped(Mesh m, std::uint32_t group, std::string name) {
  m.face_groups.assign(m.face_count(), group);
  if (!name.empty()) {
    m.group_names.resize(group + 1);
    m.group_names[group] = std::move(name);
  }
  return m;
}

/// The centroid of output face f.
Vec3d centroid(const Mesh& m, std::size_t f) {
  Vec3d c;
  for (const std::uint32_t v : m.face(f)) c = c + (1.0 / static_cast<double>(m.face_size(f))) * m.vertices[v];
  return c;
}

TEST(FaceGroups, EveryOutputFaceTakesItsSourceFacesGroup) {
  Mesh a = box({0, 0, 0}, {2, 2, 2});
  a.face_groups.resize(a.face_count());
  for (std::size_t f = 0; f < a.face_count(); ++f) a.face_groups[f] = static_cast<std::uint32_t>(f % 3);
  a.group_names = {"red", "", "green"};
  const Mesh b = grouped(box({1, 1, 1}, {3, 3, 3}), 4, "");
  const std::vector<Mesh> ops{a, b};
  for (Op op : {Op::Union, Op::Intersection, Op::Difference, Op::Xor}) {
    const BooleanResult r = run_checked(ops, op);
    ASSERT_EQ(r.mesh.face_groups.size(), r.mesh.face_count());
    // Output groups in order of first appearance: red, a's unnamed 1, green, b's unnamed 4.
    EXPECT_EQ(r.mesh.group_names, (std::vector<std::string>{"red", "", "green", ""})) << int(op);
    for (std::size_t f = 0; f < r.mesh.face_count(); ++f) {
      const Provenance p = r.provenance[f];
      const std::uint32_t expected = p.operand == 0 ? ops[0].face_groups[p.face] : 3;
      EXPECT_EQ(r.mesh.face_groups[f], expected) << "op " << int(op) << " face " << f;
    }
  }
  // Without groups anywhere the output has none.
  EXPECT_TRUE(boolean({box({0, 0, 0}, {2, 2, 2}), box({1, 1, 1}, {3, 3, 3})}, Op::Union).mesh.face_groups.empty());
}

TEST(FaceGroups, CoplanarFacesOfDifferentGroupsAreNotMerged) {
  // Two boxes side by side share their top plane z = 1; the union's top is
  // a's top on x <= 2 (a has the lower ids where they overlap) and b's on x >= 2.
  const Mesh a = box({0, 0, 0}, {2, 2, 1}), b = box({1, 0, 0}, {3, 2, 1});
  for (const bool with_groups : {false, true}) {
    const std::vector<Mesh> ops =
        with_groups ? std::vector<Mesh>{grouped(a, 0, "red"), grouped(b, 0, "blue")} : std::vector<Mesh>{a, b};
    const BooleanResult r = run_checked(ops, Op::Union);
    EXPECT_EQ(volume(r.mesh), 6.0);
    std::size_t spanning = 0;
    for (std::size_t f = 0; f < r.mesh.face_count(); ++f) {
      const Vec3d c = centroid(r.mesh, f);
      if (c.z != 1.0) continue;
      const bool from_a = r.provenance[f].operand == 0;
      double lo = 1e9, hi = -1e9;
      for (const std::uint32_t v : r.mesh.face(f)) {
        lo = std::min(lo, r.mesh.vertices[v].x);
        hi = std::max(hi, r.mesh.vertices[v].x);
      }
      spanning += lo < 2.0 && hi > 2.0;
      if (with_groups) {
        EXPECT_EQ(r.mesh.face_groups[f], from_a ? 0u : 1u);
        EXPECT_TRUE(from_a ? hi <= 2.0 : lo >= 2.0) << "a top face of one group reaches into the other's";
      }
    }
    // Merged into one region, the top is triangulated across x = 2; kept apart, never.
    if (with_groups) EXPECT_EQ(spanning, 0u);
    if (!with_groups) EXPECT_GT(spanning, 0u);
    if (with_groups) {
      EXPECT_EQ(r.mesh.group_names, (std::vector<std::string>{"red", "blue"}));
    }
  }
}

TEST(FaceGroups, NamedGroupsJoinAcrossOperandsAndLayersAndExpressionsKeepThem) {
  const std::vector<Mesh> all = four_solids();
  std::vector<Mesh> ops{grouped(all[0], 0, "steel"), grouped(all[1], 2, "brass"), grouped(all[2], 5, "steel")};
  const BooleanResult u = boolean(ops, Csg::operand(0) | Csg::operand(1) | Csg::operand(2));
  EXPECT_EQ(u.mesh.group_names, (std::vector<std::string>{"steel", "brass"}));
  for (std::size_t f = 0; f < u.mesh.face_count(); ++f)
    EXPECT_EQ(u.mesh.face_groups[f], u.provenance[f].operand == 1 ? 1u : 0u);
  for (const BooleanResult& layer : boolean_layers(ops)) {
    ASSERT_EQ(layer.mesh.face_groups.size(), layer.mesh.face_count());
    expect_watertight_if_closed(ops, {}, layer);
  }
}

TEST(FaceGroups, GroupsOfTheWrongSizeAreAnErrorNamingTheOperand) {
  Mesh a = box({0, 0, 0}, {2, 2, 2});
  a.face_groups = {1, 2};
  const std::string e = error_message([&] { boolean({box({1, 1, 1}, {3, 3, 3}), a}, Op::Union); });
  EXPECT_NE(e.find("operand 1: face_groups has 2 entries for 12 faces"), std::string::npos) << e;
}

}  // namespace
}  // namespace ember::test
