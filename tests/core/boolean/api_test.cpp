// API behaviour of ember::boolean: input validation, open operands, empty
// results, provenance, statistics and thread independence.
#include <algorithm>
#include <cctype>
#include <limits>
#include <optional>

#include "support/boolean_checks.hpp"

namespace ember::test {
namespace {

using Op = Operation;

std::string lower(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return s;
}

TEST(BooleanApi, EmptyOperandListThrows) {
  std::vector<Mesh> none;
  EXPECT_THROW(boolean(std::span<const Mesh>(none), Op::Union), Error);
  EXPECT_THROW(boolean(std::span<const Mesh>(none), Op::Intersection), Error);
}

TEST(BooleanApi, NonFiniteCoordinatesThrowWithAMessage) {
  Mesh a = box({0, 0, 0}, {1, 1, 1});
  Mesh nan = a;
  nan.vertices[3].y = std::numeric_limits<double>::quiet_NaN();
  std::string msg = lower(error_message([&] { boolean({a, nan}, Op::Union); }));
  ASSERT_NE(msg, "") << "NaN coordinate must throw ember::Error";
  EXPECT_TRUE(msg.find("nan") != std::string::npos || msg.find("finite") != std::string::npos) << msg;
  Mesh inf = a;
  inf.vertices[0].z = std::numeric_limits<double>::infinity();
  EXPECT_THROW(boolean({inf}, Op::Union), Error);
}

TEST(BooleanApi, BadFaceIndicesThrow) {
  Mesh a = box({0, 0, 0}, {1, 1, 1});
  Mesh bad = a;
  bad.indices[5] = 8;  // one past the last vertex
  EXPECT_THROW(boolean({a, bad}, Op::Union), Error);
  Mesh offs = a;
  offs.face_offsets.back() = static_cast<std::uint32_t>(offs.indices.size() + 3);  // offsets past the index buffer
  EXPECT_THROW(boolean({offs}, Op::Union), Error);
}

// Each kind of bad face is named (the validation checks every face in two
// flat passes and searches per face only for the message).
TEST(BooleanApi, BadFacesAreNamed) {
  const Mesh a = box({0, 0, 0}, {1, 1, 1});
  const auto message = [&](const Mesh& bad) { return error_message([&] { boolean({a, bad}, Op::Union); }); };
  Mesh index = a;
  index.indices[7] = 8;  // face 2, one past the last vertex
  EXPECT_NE(message(index).find("operand 1: face 2 uses vertex index 8, but the mesh has 8 vertices"),
            std::string::npos)
      << message(index);
  Mesh two = a;  // face 0 gives its third corner to face 1, which has 4
  two.face_offsets[1] = 2;
  EXPECT_NE(message(two).find("operand 1: face 0 has 2 vertices; faces need at least 3"), std::string::npos)
      << message(two);
  Mesh decreasing = a;  // face 3 ends before it starts
  decreasing.face_offsets[4] = 8;
  EXPECT_NE(message(decreasing).find("operand 1: face_offsets must not decrease (face 3)"), std::string::npos)
      << message(decreasing);
}

TEST(BooleanApi, MinKOutOfRangeThrows) {
  Mesh a = box({0, 0, 0}, {2, 2, 2}), b = box({1, 1, 1}, {3, 3, 3});
  EXPECT_THROW(boolean({a, b}, Op::AtLeastK, with_min_k(0)), Error);
  EXPECT_THROW(boolean({a, b}, Op::AtLeastK, with_min_k(3)), Error);
  EXPECT_NO_THROW(boolean({a, b}, Op::AtLeastK, with_min_k(2)));
}

Mesh open_box() {
  Mesh a = box({0, 0, 0}, {2, 2, 2});
  Mesh open;
  open.vertices = a.vertices;
  for (std::size_t f = 1; f < a.face_count(); ++f) open.add_face(a.face(f));  // drop one triangle
  return open;
}

// The error carries where the problem lies as fields, so that a caller that
// names operands its own way (the CLI, by file) need not parse the message.
TEST(BooleanApi, ErrorsCarryTheOperandFaceAndVertexAsFields) {
  const Mesh a = box({0, 0, 0}, {1, 1, 1});
  Mesh nan = a;
  nan.vertices[3].y = std::numeric_limits<double>::quiet_NaN();
  try {
    boolean({a, nan}, Op::Union);
    FAIL() << "a NaN coordinate must throw";
  } catch (const Error& e) {
    ASSERT_TRUE(e.operand().has_value());
    EXPECT_EQ(*e.operand(), 1u);
    ASSERT_TRUE(e.where().vertex.has_value());
    EXPECT_EQ(*e.where().vertex, 3u);
    EXPECT_EQ(e.problem().rfind("vertex 3 ", 0), 0u) << e.problem();
    EXPECT_EQ(std::string(e.what()), "operand 1: " + e.problem());
  }
  Mesh bad = a;
  bad.indices[5] = 8;  // face 1 (indices 3..5) uses a vertex past the end
  try {
    boolean({bad, a}, Op::Union);
    FAIL() << "a bad index must throw";
  } catch (const Error& e) {
    EXPECT_EQ(e.operand(), std::optional<std::size_t>(0));
    EXPECT_EQ(e.where().face, std::optional<std::size_t>(5 / 3));
  }
  try {
    boolean({a, open_box()}, Op::Union);
    FAIL() << "an open operand must throw";
  } catch (const Error& e) {
    EXPECT_EQ(e.operand(), std::optional<std::size_t>(1));
    EXPECT_EQ(e.problem().rfind("not closed: ", 0), 0u) << e.problem();
  }
  const Error plain("no location");
  EXPECT_FALSE(plain.operand().has_value());
  EXPECT_EQ(plain.problem(), "no location");
  EXPECT_EQ(Error("bad header", {.file = "a.obj"}).what(), std::string("a.obj: bad header"));
}

TEST(BooleanApi, OpenOperandThrowsByDefault) {
  Mesh b = box({1, 1, 1}, {3, 3, 3});
  std::string msg = error_message([&] { boolean({open_box(), b}, Op::Union); });
  EXPECT_NE(msg, "") << "an open operand must be rejected without allow_open";
}

TEST(BooleanApi, OpenOperandWithAllowOpenWarns) {
  Mesh b = box({5, 5, 5}, {6, 6, 6});
  BooleanOptions o;
  o.allow_open = true;
  BooleanResult r;
  ASSERT_NO_THROW(r = boolean({open_box(), b}, Op::Union, o));
  EXPECT_FALSE(r.warnings.empty());
  EXPECT_EQ(face_problems(r.mesh), "");
  EXPECT_EQ(r.provenance.size(), r.mesh.face_count());
  // The closed, disjoint operand is reproduced.
  bool from_b = false;
  for (const Provenance& p : r.provenance) from_b = from_b || p.operand == 1;
  EXPECT_TRUE(from_b);
  // Closed inputs produce no warnings.
  EXPECT_TRUE(boolean({b}, Op::Union).warnings.empty());
}

TEST(BooleanApi, EmptyResultIsAValidEmptyMesh) {
  Mesh a = box({0, 0, 0}, {1, 1, 1}), b = box({3, 3, 3}, {4, 4, 4});
  auto r = boolean({a, b}, Op::Intersection);
  EXPECT_TRUE(r.mesh.empty());
  EXPECT_EQ(r.mesh.face_count(), 0u);
  EXPECT_EQ(r.mesh.face_offsets, std::vector<std::uint32_t>{0});
  EXPECT_TRUE(r.mesh.indices.empty());
  EXPECT_TRUE(r.provenance.empty());
  EXPECT_EQ(r.stats.output_polygons, 0u);
  // b - (a union b) is empty as well.
  EXPECT_TRUE(boolean({b, a, b}, Op::Difference).mesh.empty());
}

TEST(BooleanApi, EmptyOperandMeshIsTheEmptySet) {
  Mesh a = box({0, 0, 0}, {2, 3, 4}), e;
  EXPECT_EQ(volume(run_checked({a, e}, Op::Union, {}, 0).mesh), 24.0);
  EXPECT_EQ(volume(run_checked({a, e}, Op::Difference, {}, 0).mesh), 24.0);
  EXPECT_TRUE(run_checked({a, e}, Op::Intersection).mesh.empty());
}

TEST(BooleanApi, DisjointUnionReproducesTheInputsWithProvenance) {
  Mesh a = box_quads({0, 0, 0}, {1, 1, 1}), b = box_quads({3, 0, 0}, {4, 2, 1});
  std::vector<Mesh> ops{a, b};
  auto r = run_checked(ops, Op::Union, {}, 0);
  EXPECT_EQ(volume(r.mesh), 3.0);
  EXPECT_EQ(provenance_plane_violations(ops, r), 0);
  // Every input face is represented (polygons stay subsets of input faces).
  std::vector<std::vector<bool>> seen{std::vector<bool>(6), std::vector<bool>(6)};
  for (const Provenance& p : r.provenance) seen[p.operand][p.face] = true;
  for (const auto& s : seen)
    for (bool x : s) EXPECT_TRUE(x);
}

TEST(BooleanApi, ProvenanceOfDifferenceNamesBothOperandsAndFlipsNormals) {
  std::vector<Mesh> ops{box({0, 0, 0}, {4, 4, 4}), box({1, 1, 2}, {3, 3, 6})};
  auto r = run_checked(ops, Op::Difference, {}, 0);
  EXPECT_EQ(volume(r.mesh), 64.0 - 8.0);
  EXPECT_EQ(provenance_plane_violations(ops, r), 0);
  // Faces from the subtracted operand bound the pocket: their normals point
  // opposite to the input face normals (into the removed box).
  int from_b = 0;
  for (std::size_t f = 0; f < r.mesh.face_count(); ++f) {
    if (r.provenance[f].operand != 1) continue;
    ++from_b;
    auto of = r.mesh.face(f);
    auto sf = ops[1].face(r.provenance[f].face);
    Vec3l n_out = cross(to_l(r.mesh.vertices[of[1]]) - to_l(r.mesh.vertices[of[0]]),
                        to_l(r.mesh.vertices[of[2]]) - to_l(r.mesh.vertices[of[0]]));
    Vec3l n_in = cross(to_l(ops[1].vertices[sf[1]]) - to_l(ops[1].vertices[sf[0]]),
                       to_l(ops[1].vertices[sf[2]]) - to_l(ops[1].vertices[sf[0]]));
    EXPECT_LT(dot(n_out, n_in), 0) << "face " << f;
  }
  EXPECT_GT(from_b, 0);
}

TEST(BooleanApi, StatsCountInputTriangles) {
  Mesh a = box({0, 0, 0}, {2, 2, 2}), b = box({1, 1, 1}, {3, 3, 3});
  auto r = boolean({a, b}, Op::Union);
  EXPECT_EQ(r.stats.input_triangles, 24u);
  EXPECT_EQ(r.stats.dropped_degenerate, 0u);
  EXPECT_GE(r.stats.time_ms, 0.0);
  EXPECT_GE(r.stats.threads, 1);
}

// The figures of how the run went sit in a list looked up by name; the CLI's
// --stats prints them in this order.
TEST(BooleanApi, DiagnosticsNameTheRouteAndThePhases) {
  const Mesh a = box({0, 0, 0}, {2, 2, 2}), b = box({1, 1, 1}, {3, 3, 3});
  const BooleanResult r = boolean({a, b}, Op::Union);
  std::vector<std::string> names;
  for (const Diagnostic& d : r.stats.diagnostics) names.push_back(d.name);
  const std::vector<std::string> expected{"merged_triangles",  "solid_path", "direct_mesh",      "tjunctions_resolved",
                                          "collinear_removed", "regions",    "fallback_regions", "setup_ms",
                                          "proof_ms",          "solve_ms",   "output_ms",        "weld_ms",
                                          "tjunction_ms",      "regions_ms", "triangulate_ms"};
  EXPECT_EQ(names, expected);
  EXPECT_EQ(r.stats.diagnostic("solid_path"), 1.0);  // two boxes are proven solid
  EXPECT_EQ(r.stats.diagnostic("no such figure"), 0.0);
  double phases = 0;
  for (const char* p : {"setup_ms", "proof_ms", "solve_ms", "output_ms"}) {
    EXPECT_GE(r.stats.diagnostic(p), 0.0) << p;
    phases += r.stats.diagnostic(p);
  }
  EXPECT_LE(phases, r.stats.time_ms * 1.0001 + 1e-6);
  BooleanOptions general;
  general.route = BooleanOptions::Route::General;
  const BooleanResult g = boolean({a, b}, Op::Union, general);
  EXPECT_EQ(g.stats.diagnostic("solid_path"), 0.0);
  EXPECT_EQ(g.stats.output_polygons, r.stats.output_polygons);
}

TEST(BooleanApi, ResultIndependentOfThreadCount) {
  auto [xs, ys] = beams(6);
  std::vector<std::vector<Mesh>> cases{{xs, ys},
                                       snapped({icosphere({0, 0, 0}, 1, 3), torus({0.5, 0, 0}, 1, 0.4, 32, 16)})};
  for (const auto& ops : cases)
    for (Op op : {Op::Union, Op::Intersection, Op::Difference}) {
      BooleanOptions one, two, all;
      one.threads = 1;
      two.threads = 2;
      all.threads = 0;
      auto r1 = boolean(ops, op, one), r2 = boolean(ops, op, two), r0 = boolean(ops, op, all);
      EXPECT_EQ(r1.stats.threads, 1);
      EXPECT_TRUE(r1.mesh == r2.mesh) << "op " << int(op);
      EXPECT_TRUE(r1.mesh == r0.mesh) << "op " << int(op);
      ASSERT_EQ(r1.provenance.size(), r2.provenance.size());
      for (std::size_t i = 0; i < r1.provenance.size(); ++i) {
        EXPECT_EQ(r1.provenance[i].operand, r2.provenance[i].operand);
        EXPECT_EQ(r1.provenance[i].face, r2.provenance[i].face);
      }
    }
}

TEST(BooleanApi, RepeatedCallsAreDeterministic) {
  auto ops = snapped({icosphere({0, 0, 0}, 1, 3), icosphere({0.6, 0.1, 0}, 1, 3)});
  auto a = boolean(ops, Op::Xor), b = boolean(ops, Op::Xor);
  EXPECT_TRUE(a.mesh == b.mesh);
}

TEST(BooleanApi, OperandOrderDoesNotChangeSymmetricOperations) {
  std::vector<Mesh> ab{box({0, 0, 0}, {3, 3, 3}), icosphere({3, 3, 3}, 2, 2)};
  snap_to_grid(ab);
  std::vector<Mesh> ba{ab[1], ab[0]};
  for (Op op : {Op::Union, Op::Intersection, Op::Xor}) {
    double v1 = volume(run_checked(ab, op).mesh), v2 = volume(run_checked(ba, op).mesh);
    EXPECT_TRUE(close_rel(v1, v2, 1e-12)) << "op " << int(op);
  }
}

TEST(BooleanApi, LargeAndSmallScalesKeepRelativeAccuracy) {
  // Quantization is relative to the inputs' extent: the same configuration at
  // 1e-6 and 1e6 scale gives the same relative volumes (power-of-two scale
  // factors keep snapped coordinates exact).
  for (double s : {0x1p-20, 1.0, 0x1p20}) {
    auto ops = snapped({scale(icosphere({0, 0, 0}, 1, 3), s), scale(icosphere({0.5, 0.2, 0}, 1, 3), s)});
    double va = volume(ops[0]), vb = volume(ops[1]);
    double u = volume(run_checked(ops, Op::Union).mesh), i = volume(run_checked(ops, Op::Intersection).mesh);
    EXPECT_TRUE(close_rel(u + i, va + vb, 1e-9)) << "scale " << s;
    EXPECT_GT(i, 0.0);
  }
}

}  // namespace
}  // namespace ember::test
