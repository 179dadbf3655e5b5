// The solid proof's per-component check traces one operand's triangles
// through its tree (own_winding_from_outside) instead of scanning the root
// soup (classify_polygon). It runs once the operand is known closed and free
// of self-intersections, where the operand's winding number is constant on
// either side of each of its triangles: where both find a path, they must
// give the same winding numbers in front of and behind the triangle,
// whatever other operands (crossing it, with coplanar copies) lie around.
#include <gtest/gtest.h>

#include <random>
#include <vector>

#include "core/route/general/leaf.hpp"
#include "core/route/solid/solid_trace.hpp"
#include "core/search/triangle_tree.hpp"

namespace ember::core {
namespace {

/// The four faces of tetrahedron (a, b, c, d), all outward or all inward
/// (by the side of (a, b, c)'s plane d is on): closed either way.
void add_tetrahedron(const std::array<IntPoint, 4>& v, std::vector<std::array<IntPoint, 3>>& out) {
  out.push_back({v[0], v[1], v[2]});
  out.push_back({v[0], v[3], v[1]});
  out.push_back({v[1], v[3], v[2]});
  out.push_back({v[2], v[3], v[0]});
}

TEST(SolidTrace, OwnWindingThroughTheTreeIsTheSoupScans) {
  constexpr std::size_t kOperands = 3, kCells = 4, kCell = 60, kShapes = 24;
  std::mt19937_64 rng(11);
  std::uniform_int_distribution<std::int64_t> in_cell(2, static_cast<std::int64_t>(kCell) - 2);
  // Per operand, tetrahedra in distinct cells of a 4 x 4 x 4 grid (so they
  // never meet), some inside out, some with a smaller one nested inside
  // (vertices (2 v_i + the others) / 5 of the outer one's, coordinates
  // scaled by 5 so they stay integers). The operands' grids are shifted by
  // different offsets, so their tetrahedra cross; operand 1 also has a copy
  // of one of operand 0's: coplanar faces of another operand at the targets.
  std::vector<std::array<IntPoint, 3>> corners;
  std::vector<std::uint32_t> begin{0};
  std::array<IntPoint, 4> first_of_operand0{};
  for (std::size_t o = 0; o < kOperands; ++o) {
    std::vector<std::size_t> cells(kCells * kCells * kCells);
    for (std::size_t c = 0; c < cells.size(); ++c) cells[c] = c;
    std::shuffle(cells.begin(), cells.end(), rng);
    const auto offset = static_cast<std::int64_t>(17 * o);
    for (std::size_t s = 0; s < kShapes; ++s) {
      const std::size_t c = cells[s];
      const std::int64_t cx = static_cast<std::int64_t>(c % kCells * kCell) + offset,
                         cy = static_cast<std::int64_t>(c / kCells % kCells * kCell) + offset,
                         cz = static_cast<std::int64_t>(c / kCells / kCells * kCell) + offset;
      std::array<IntPoint, 4> v;
      do {
        for (IntPoint& p : v) p = {5 * (cx + in_cell(rng)), 5 * (cy + in_cell(rng)), 5 * (cz + in_cell(rng))};
        const std::array<std::int64_t, 3> n = grid_normal(v[0], v[1], v[2]);
        if (n[0] * (v[3].x - v[0].x) + n[1] * (v[3].y - v[0].y) + n[2] * (v[3].z - v[0].z) != 0) break;
      } while (true);
      if (s % 3 == 1) std::swap(v[1], v[2]);  // inside out
      add_tetrahedron(v, corners);
      if (o == 0 && s == 0) first_of_operand0 = v;
      if (s % 4 == 2) {
        std::array<IntPoint, 4> inner;
        for (int i = 0; i < 4; ++i) {
          const IntPoint& a = v[static_cast<std::size_t>(i)];
          const IntPoint &b = v[static_cast<std::size_t>((i + 1) % 4)], &d = v[static_cast<std::size_t>((i + 2) % 4)],
                         &e = v[static_cast<std::size_t>((i + 3) % 4)];
          inner[static_cast<std::size_t>(i)] = {(2 * a.x + b.x + d.x + e.x) / 5, (2 * a.y + b.y + d.y + e.y) / 5,
                                                (2 * a.z + b.z + d.z + e.z) / 5};
        }
        add_tetrahedron(inner, corners);
      }
    }
    if (o == 1) add_tetrahedron(first_of_operand0, corners);
    begin.push_back(static_cast<std::uint32_t>(corners.size()));
  }
  Subproblem pb;
  pb.box.lo = {-1, -1, -1};
  pb.box.hi = {2000, 2000, 2000};  // beyond every coordinate (5 * (4 * 60 + 2 * 17)): outside everything
  for (int a = 0; a < 3; ++a) pb.ref.num[a] = 2 * pb.box.lo[a] + 1;
  pb.ref.shift = 1;
  pb.ref_w.assign(kOperands, 0);
  std::vector<TriangleTree> trees;
  for (std::uint32_t o = 0; o < kOperands; ++o) {
    std::vector<Box32> boxes;
    for (std::uint32_t i = begin[o]; i < begin[o + 1]; ++i) {
      pb.soup.push_back(unbuilt_triangle(corners[i], i, o));
      boxes.push_back(box_of(corners[i]));
    }
    trees.emplace_back(boxes);
  }
  std::size_t compared = 0, inside = 0;
  for (std::uint32_t o = 0; o < kOperands; ++o)
    for (std::uint32_t t = begin[o]; t < begin[o + 1]; ++t) {
      Wnv want_front, want_back;
      const bool scanned = classify_polygon(pb, pb.soup[t], want_front, want_back);
      TraceScratch sc;
      Polygon built;
      int front = 0, back = 0;
      const bool traced =
          own_winding_from_outside(corners, trees[o], begin[o], pb.box, kOperands, built_polygon(pb.soup[t], built), o,
                                   std::uint64_t{t} << 20, front, back, sc);
      if (!scanned || !traced) continue;
      ++compared;
      EXPECT_EQ(front, want_front[o]) << "triangle " << t;
      EXPECT_EQ(back, want_back[o]) << "triangle " << t;
      // Outward: 0 in front, 1 behind; inside out: -1 and 0; a nested one adds its outer's.
      EXPECT_EQ(back - front, 1) << "triangle " << t;
      inside += front != 0 && back != 0;
    }
  // The check means something: (nearly) every triangle gets both answers,
  // and the nested ones see their outer tetrahedron's winding number.
  EXPECT_GT(compared, 250u);
  EXPECT_GT(inside, 20u);
}

}  // namespace
}  // namespace ember::core
