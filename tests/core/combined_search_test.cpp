// The combined broad phase (src/core/combined_search.hpp): one traversal
// for the proof's contact searches and the solid path's partner search. Where
// it decides, its partners must be exactly find_partners' and every searched
// operand free of improper contacts; where an operand meets itself or a
// frame applies it must decline, leaving the separate searches what they
// need (the prepared triangles, the diagonals, the sampled frames).
#include <gtest/gtest.h>

#include <tbb/task_arena.h>

#include <atomic>
#include <random>
#include <vector>

#include "contact_test_util.hpp"
#include "core/combined_search.hpp"
#include "core/contact_search.hpp"
#include "core/grid_input.hpp"
#include "core/input_soup.hpp"
#include "core/operand_trees.hpp"
#include "core/solid_path.hpp"
#include "support/shapes.hpp"

namespace ember::test {
namespace {

/// The set-up's grid triangles of `ops` and the second operand's vertex-id
/// base (its ids offset past the first's), as boolean() makes them.
struct Grid {
  core::InputTriangles in;
  std::uint32_t second_base = 0;
};

Grid grid_of(const std::vector<Mesh>& ops) {
  const core::UsedVertices used = core::used_vertices(ops);
  const Quantizer q = core::fit_used_vertices(ops, used);
  const core::GridInput gi = core::to_grid(ops, q, used);
  return {core::build_grid_triangles(gi, core::match_edges(gi)), static_cast<std::uint32_t>(gi.vertex_count[0])};
}

/// Grid triangles from two soups: every corner its own vertex id, no
/// manifold neighbours (no star is certified).
Grid grid_of(const std::vector<Tri>& a, const std::vector<Tri>& b) {
  Grid g;
  g.in.operand_begin = {0, static_cast<std::uint32_t>(a.size()), static_cast<std::uint32_t>(a.size() + b.size())};
  for (const std::vector<Tri>* soup : {&a, &b})
    for (const Tri& t : *soup) {
      const auto id = static_cast<std::uint32_t>(3 * g.in.grid.corners.size());
      g.in.grid.corners.push_back(t);
      g.in.grid.vertex_ids.push_back({id, id + 1, id + 2});
      g.in.grid.neighbors.push_back({core::kNoNeighbor, core::kNoNeighbor, core::kNoNeighbor});
    }
  return g;
}

/// combined_broad_phase as boolean() calls it (trees without diagonals).
core::CombinedBroadPhase combine(const Grid& g, core::OperandTrees& trees, std::array<bool, 2> searched = {true, true}) {
  trees = core::build_operand_trees(g.in.operand_begin, g.in.grid.corners, false, true);
  return core::combined_broad_phase(g.in.grid, trees, searched, g.second_base);
}

/// find_partners' answer for the same operands.
core::Partners separate_partners(const Grid& g) {
  const core::OperandTrees trees = core::build_operand_trees(g.in.operand_begin, g.in.grid.corners);
  const std::atomic<bool> never{false};
  return core::find_partners(g.in.grid, trees, g.in.grid.corners.size(), never);
}

/// Random small triangles around the origin (a crowded soup: many meet).
std::vector<Tri> crowded_soup(std::size_t count, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_int_distribution<std::int64_t> at(-200, 200), step(-60, 60);
  std::vector<Tri> out;
  while (out.size() < count) {
    const IntPoint p{at(rng), at(rng), at(rng)};
    const Tri t{p, IntPoint{p.x + step(rng), p.y + step(rng), p.z + step(rng)},
                IntPoint{p.x + step(rng), p.y + step(rng), p.z + step(rng)}};
    if (!degenerate(t)) out.push_back(t);
  }
  return out;
}

/// A mesh turned by `angle` about z.
Mesh turned(const Mesh& m, double angle) {
  return map_vertices(m, [angle](Vec3d p) {
    const double c = std::cos(angle), s = std::sin(angle);
    return Vec3d{c * p.x - s * p.y, s * p.x + c * p.y, p.z};
  });
}

TEST(CombinedSearch, FindsThePartnersOfTheSeparateSearchAtEveryThreadCount) {
  // Solid operands whose surfaces crowd each other (a mesh and its copy
  // turned slightly: the bunny pair's case): partners, equal to
  // find_partners'. Operands that only cross or touch: it steps aside at
  // once (nothing prepared, the diagonals built for the separate searches).
  const Mesh sphere = icosphere({0, 0, 0}, 1.0, 4), ring = torus({0, 0, 0}, 1.0, 0.3, 48, 16);
  struct Case {
    std::vector<Mesh> ops;
    bool crowded;
  };
  const std::vector<Case> cases{
      {{sphere, turned(sphere, 0.02)}, true},
      {{ring, turned(ring, 0.03)}, true},
      {{ring, translate(icosphere({1.0, 0, 0}, 0.45, 3), {0, 0, 0.05})}, false},
      {{box({0, 0, 0}, {1, 1, 1}), box({1, 0.25, 0.25}, {2, 0.75, 0.75})}, false},  // touching faces
  };
  for (std::size_t c = 0; c < cases.size(); ++c) {
    const Grid g = grid_of(cases[c].ops);
    const core::Partners want = separate_partners(g);
    EXPECT_FALSE(want.ids.empty()) << "case " << c << ": the operands should meet";
    for (const int threads : {1, 2, 4}) {
      core::OperandTrees trees;
      core::CombinedBroadPhase found;
      tbb::task_arena(threads).execute([&] { found = combine(g, trees); });
      EXPECT_TRUE(found.prepared.empty()) << "case " << c << ": nothing left for separate searches";
      if (!cases[c].crowded) {
        EXPECT_FALSE(found.partners.has_value()) << "case " << c;
        EXPECT_EQ(trees.diagonals.size(), 2u) << "case " << c;
        EXPECT_TRUE(trees.sliver.empty()) << "case " << c << ": no frame sampled (the searches sample their own)";
        continue;
      }
      ASSERT_TRUE(found.partners.has_value()) << "case " << c << ", " << threads << " threads";
      EXPECT_EQ(found.partners->begin, want.begin) << "case " << c;
      EXPECT_EQ(found.partners->ids, want.ids) << "case " << c;
      EXPECT_TRUE(trees.diagonals.empty()) << "case " << c;
    }
  }
}

TEST(CombinedSearch, DeclinesWhereASearchedOperandMeetsItself) {
  // Two overlapping spheres in each operand (the second turned slightly, so
  // that the surfaces crowd each other): each contact search must count
  // them, so the combined search leaves them the triangles it prepared
  // (stars certified, the second operand's ids offset), the diagonals and
  // the sampled frames.
  const Mesh pair = merge({icosphere({0, 0, 0}, 1.0, 3), icosphere({0.5, 0, 0}, 1.0, 3)});
  const std::vector<Mesh> ops{pair, turned(pair, 0.02)};
  const Grid g = grid_of(ops);
  core::OperandTrees trees;
  const core::CombinedBroadPhase found = combine(g, trees);
  EXPECT_FALSE(found.partners.has_value());
  ASSERT_EQ(found.prepared.size(), g.in.grid.corners.size());
  ASSERT_EQ(trees.diagonals.size(), 2u);
  ASSERT_EQ(trees.sliver.size(), 2u);
  EXPECT_TRUE(trees.sliver[0].sampled && trees.sliver[1].sampled);
  // The prepared triangles are what check_solid would prepare: same
  // corners, normals and stars; ids equal up to the second operand's offset.
  for (std::uint32_t o = 0; o < 2; ++o) {
    const std::span<const core::ContactTriangle> got = found.of(trees, o);
    const std::uint32_t begin = g.in.operand_begin[o];
    ASSERT_EQ(got.size(), g.in.operand_begin[o + 1] - begin);
    std::vector<std::uint32_t> members(got.size());
    for (std::uint32_t i = 0; i < members.size(); ++i) members[i] = begin + i;
    std::vector<core::ContactTriangle> want(members.size());
    core::prepare_contact_triangles(g.in.grid, members, want);
    for (std::size_t i = 0; i < got.size(); ++i) {
      EXPECT_EQ(got[i].corners, want[i].corners);
      EXPECT_EQ(got[i].n, want[i].n);
      EXPECT_EQ(got[i].embedded, want[i].embedded);
      for (int k = 0; k < 3; ++k) EXPECT_EQ(got[i].id[k], want[i].id[k] + (o == 1 ? g.second_base : 0));
    }
    // The counts the separate search reports, from the prepared triangles.
    const core::ContactSearchResult with = core::find_contacts(got, 1000, &trees.tree[o], nullptr, &trees.diagonals[o],
                                                               &trees.sliver[o]);
    const core::ContactSearchResult without = core::find_contacts(want, 1000);
    EXPECT_EQ(with.pairs, without.pairs) << "operand " << o;
    EXPECT_GT(with.pairs, 0u) << "operand " << o;
  }
}

TEST(CombinedSearch, APromisedOperandsOwnPairsAreNotSearched) {
  // A crowded soup meets itself everywhere; promised solid (not searched),
  // its own pairs are not tested and the meeting pairs with the other
  // operand are still found, exactly. Searched, it makes the search decline.
  const Grid g = grid_of(crowded_soup(400, 7), crowded_soup(300, 8));
  const core::Partners want = separate_partners(g);
  EXPECT_FALSE(want.ids.empty());
  for (const std::array<bool, 2> searched : {std::array<bool, 2>{false, false}, std::array<bool, 2>{true, false},
                                             std::array<bool, 2>{false, true}}) {
    core::OperandTrees trees;
    const core::CombinedBroadPhase found = combine(g, trees, searched);
    if (searched[0] || searched[1]) {
      EXPECT_FALSE(found.partners.has_value()) << searched[0] << searched[1];
      continue;
    }
    ASSERT_TRUE(found.partners.has_value());
    EXPECT_EQ(found.partners->begin, want.begin);
    EXPECT_EQ(found.partners->ids, want.ids);
  }
}

TEST(CombinedSearch, DeclinesWhereASliverFrameApplies) {
  // A rod of slivers off the axes gets a frame in its own search
  // (sliver_frame), which the combined search does not have: beside another
  // such rod (crowding it) it declines, and leaves the frame sampled for
  // that search. Not searched (promised), the second rod samples none.
  const Grid g = grid_of(sliver_rod(600, IntPoint{0, 0, 0}, 41), sliver_rod(600, IntPoint{0, 0, 0}, 42));
  core::OperandTrees trees;
  const core::CombinedBroadPhase found = combine(g, trees, {true, false});
  EXPECT_FALSE(found.partners.has_value());
  ASSERT_EQ(trees.sliver.size(), 2u);
  EXPECT_TRUE(trees.sliver[0].sampled);
  EXPECT_TRUE(trees.sliver[0].frame.has_value());
  EXPECT_FALSE(trees.sliver[1].sampled);
  EXPECT_EQ(trees.diagonals.size(), 2u);
}

}  // namespace
}  // namespace ember::test
