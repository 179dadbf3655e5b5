// The T-junction search's shortcut (core/mesh/tjunctions.cpp,
// whole_solid_edge): with two operands, an edge between two whole input
// triangles of a solid operand, on a manifold edge of it, is searched for the
// other operand's vertices only. These cases put a vertex exactly inside such
// an edge, from the other operand (must be found in the other operand's
// part) and from the same operand on an edge with three uses (must not be
// searched that way at all); the set-up's manifold bits are checked first.
#include <gtest/gtest.h>

#include "support/boolean_checks.hpp"
#include "core/input/grid_input.hpp"
#include "core/input/input_triangles.hpp"
#include "core/output/output_vertices.hpp"
#include "core/output/exact_weld.hpp"
#include "core/output/tjunctions.hpp"
#include "core/output/vertex_index.hpp"
#include "geometry/clip.hpp"
#include "geometry/polygon.hpp"

namespace ember::test {
namespace {

/// The set-up's manifold bits of every triangle of `ops`, in GridInput order.
std::vector<std::uint8_t> manifold_bits(std::span<const Mesh> ops) {
  const core::UsedVertices used = core::used_vertices(ops);
  const Quantizer q = core::fit_used_vertices(ops, used);
  const core::GridInput gi = core::to_grid(ops, q, used);
  return core::match_edges(gi).manifold;
}

TEST(TjunctionSearch, ManifoldBitsMarkEdgesWithExactlyOneOppositeUse) {
  // A closed box: every edge of its 12 triangles is manifold.
  const std::vector<Mesh> closed{box({0, 0, 0}, {1, 1, 1})};
  for (const std::uint8_t bits : manifold_bits(closed)) EXPECT_EQ(bits, 7);
  // Two boxes sharing the edge x = y = 2 (one operand): the four triangles
  // on that edge lose its bit, every other edge keeps it.
  const std::vector<Mesh> shared{merge({box({0, 0, 0}, {2, 2, 2}), box({2, 2, 0}, {4, 4, 2})})};
  const std::vector<std::uint8_t> bits = manifold_bits(shared);
  ASSERT_EQ(bits.size(), 24u);
  int cleared = 0;
  for (const std::uint8_t b : bits) cleared += 3 - std::popcount(static_cast<unsigned>(b));
  EXPECT_EQ(cleared, 4);
  // An open box (one triangle removed): the three triangles next to the hole
  // lose the bit of the edge they shared with it.
  Mesh open = box({0, 0, 0}, {1, 1, 1});
  open.indices.resize(open.indices.size() - 3);
  open.face_offsets.pop_back();
  const std::vector<Mesh> holed{open};
  const std::vector<std::uint8_t> hb = manifold_bits(holed);
  int open_edges = 0;
  for (const std::uint8_t b : hb) open_edges += 3 - std::popcount(static_cast<unsigned>(b));
  EXPECT_EQ(open_edges, 3);
}

TEST(TjunctionSearch, OtherOperandsApexInsideAWholeSolidEdgeIsInserted) {
  // The tetrahedron's apex (2, 0, 0) rests on the box's edge y = z = 0,
  // between two whole triangles of a solid operand in different planes
  // (neither region merging nor re-triangulation would touch them): the
  // search looks at the tetrahedron's vertices only and must find it.
  const std::vector<Mesh> ops{box({0, 0, 0}, {4, 4, 2}), tetrahedron({2, 0, 0}, {1, -2, -1}, {3, -2, -1}, {2, -1, -2})};
  for (const Operation op : {Operation::Union, Operation::Xor}) {
    const BooleanResult r = run_checked(ops, op);
    EXPECT_EQ(r.stats.solid_operands, 2u);
    EXPECT_GE(r.stats.diagnostic("tjunctions_resolved"), 1u);
    EXPECT_DOUBLE_EQ(volume(r.mesh), 32.0 + volume(ops[1]));
  }
}

/// Step 2 alone on hand-made output polygons: T1 and T2, whole triangles of
/// operand `o` on the segment a = (0,0,0) -> b = (4,0,0) (edge 0 of both, in
/// opposite directions), and `extra`, pieces with a vertex at (2,0,0) inside
/// that segment. `manifold` is what the set-up would claim about edge 0 of T1
/// and T2. Returns how many vertices step 2 inserted.
struct StepTwoCase {
  std::vector<std::array<IntPoint, 3>> corners;  // by id; stable addresses (reserved)
  std::vector<core::OutputPolygon> polys;
  StepTwoCase() { corners.reserve(8); }
  void whole(const std::array<IntPoint, 3>& c, std::uint32_t operand) {
    corners.push_back(c);
    core::OutputPolygon p;
    p.corners = &corners.back();
    p.id = static_cast<std::uint32_t>(corners.size() - 1);
    p.operand = operand;
    polys.push_back(std::move(p));
  }
  /// Triangle c cut at x = 2, both halves as explicit pieces.
  void halves(const std::array<IntPoint, 3>& c, std::uint32_t operand) {
    corners.push_back(c);
    const Polygon tri = *make_triangle(c[0], c[1], c[2]);
    Polygon neg, pos;
    ASSERT_EQ(clip(tri, axis_plane(0, 2), neg, pos), ClipSide::Both);
    for (const Polygon* half : {&neg, &pos}) {
      core::OutputPolygon p;
      p.corners = &corners.back();
      p.id = static_cast<std::uint32_t>(corners.size() - 1);
      p.operand = operand;
      p.vertices.assign(half->vertices.begin(), half->vertices.end());
      polys.push_back(std::move(p));
    }
  }
  std::size_t inserted(bool manifold) const {
    core::InputTopology topology;
    topology.solid = {1, 1};
    std::vector<std::uint8_t> bits(corners.size(), 6);  // edges 1 and 2 manifold everywhere
    if (manifold) bits[0] = bits[1] = 7;
    topology.manifold_edges = bits;
    const Quantizer q = Quantizer::fit_box({-10, -10, -10}, {10, 10, 10});
    const core::OutputVertices verts = core::exact_weld(polys, q);
    const core::VertexIndex index = core::index_output_vertices(polys, verts, &topology);
    const core::EdgePairs pairs = core::group_edges_by_pair(verts.corners);
    std::size_t n = 0;
    core::insert_tjunction_vertices(polys, verts, index, pairs, n, &topology);
    return n;
  }
};

constexpr IntPoint kA{0, 0, 0}, kB{4, 0, 0};

TEST(TjunctionSearch, WholeSolidEdgesSearchTheOtherOperandOnly) {
  for (const std::uint32_t o : {0u, 1u}) {
    // A third triangle of the same operand on the segment, cut at its middle:
    // the segment then has three input uses, so the set-up clears the bit
    // and the middle vertex is inserted into T1 and T2.
    StepTwoCase same;
    same.whole({kA, kB, {0, 4, 0}}, o);
    same.whole({kB, kA, {0, 0, 4}}, o);
    same.halves({kA, kB, {0, -4, -4}}, o);
    same.whole({{{9, 9, 9}, {9, 8, 9}, {8, 9, 9}}}, 1 - o);
    EXPECT_EQ(same.inserted(false), 2u) << "operand " << o;
    // Were the bit set, only the other operand's vertices would be searched:
    // the shortcut is in effect and the set-up's bit is what keeps it sound.
    EXPECT_EQ(same.inserted(true), 0u) << "operand " << o;
    // The other operand's piece with a vertex there is found with the bit set.
    StepTwoCase other;
    other.whole({kA, kB, {0, 4, 0}}, o);
    other.whole({kB, kA, {0, 0, 4}}, o);
    other.halves({{{0, -4, -4}, {4, -4, 4}, {2, 0, 0}}}, 1 - o);
    EXPECT_EQ(other.inserted(true), 2u) << "operand " << o;
    EXPECT_EQ(other.inserted(false), 2u) << "operand " << o;
  }
}

}  // namespace
}  // namespace ember::test
