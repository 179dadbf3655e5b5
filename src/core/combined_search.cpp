// One broad phase for the proof and the solid path (combined_search.hpp).
#include "core/combined_search.hpp"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_invoke.h>

#include <algorithm>
#include <cassert>
#include <numeric>
#include <vector>

#include "core/contact_search.hpp"
#include "core/leaf_diagonals.hpp"
#include "core/triangle_tree.hpp"

namespace ember::core {

namespace {

/// Samples the frames the separate searches would filter by (each
/// searched operand's sliver frame, the pair's common frame) into `trees`,
/// where those searches find them if they run: whether any was found. The
/// three samples side by side (one can be a few milliseconds: EMBER case
/// 16's common frame, whose sample meets its slivers by the hundreds).
bool sample_frames(const GridTriangles& grid, OperandTrees& trees, std::array<bool, 2> searched) {
  const std::span<const std::array<IntPoint, 3>> corners(grid.corners);
  const auto own = [&](std::size_t o) { return corners.subspan(trees.begin[o], trees.begin[o + 1] - trees.begin[o]); };
  trees.sliver.assign(2, {});
  const auto sliver = [&](std::size_t o) {
    if (searched[o] && !own(o).empty()) trees.sliver[o] = {true, sliver_frame(own(o), trees.tree[o])};
  };
  const TriangleTree &a = trees.tree[0], &b = trees.tree[1];
  tbb::parallel_invoke([&] { sliver(0); }, [&] { sliver(1); },
                       [&] {
                         // find_partners samples none where the operands' boxes are apart.
                         if (!a.empty() && !b.empty() && overlap(a.node(0), b.node(0)))
                           trees.partner = {true, partner_frame(own(0), own(1), b)};
                       });
  return trees.sliver[0].frame || trees.sliver[1].frame || trees.partner.frame;
}

/// Triangles of each operand sampled for crowded().
constexpr std::size_t kCrowdSamples = 32;

/// Whether the operands' surfaces crowd each other: at least 3 in 4 of a
/// sample of each one's triangles (evenly spaced, kCrowdSamples) have a box
/// meeting a box of the other's. Then one tree over both meets the pairs of both kinds in
/// the same leaves (the bunny pair, a mesh and its copy turned by 1 degree:
/// every sample). Where the operands meet along a curve (the benchmark's
/// pool pairs: a few in a hundred) the tree over both mixes two surfaces in
/// leaves that each one's own tree keeps apart, and one search over it
/// costs more than the separate ones (pair011: 119 M instructions against
/// 92 + 19 M).
bool crowded(const GridTriangles& grid, const OperandTrees& trees) {
  for (std::size_t o = 0; o < 2; ++o) {
    const std::size_t first = trees.begin[o], count = trees.begin[o + 1] - first;
    const TriangleTree& other = trees.tree[1 - o];
    if (count == 0 || other.empty()) return false;
    // Stops at the first miss past a quarter of the sample (the usual
    // answer, no, after a few queries).
    const std::size_t step = std::max<std::size_t>(1, count / kCrowdSamples), samples = (count + step - 1) / step;
    std::size_t missed = 0;
    for (std::size_t i = 0; i < count; i += step) {
      bool meets = false;
      other.for_each_overlapping(box_of(grid.corners[first + i]), [&](std::uint32_t) { meets = true; });
      if (!meets && 4 * ++missed > samples) return false;
    }
  }
  return true;
}

}  // namespace

CombinedBroadPhase combined_broad_phase(const GridTriangles& grid, OperandTrees& trees, std::array<bool, 2> searched,
                                        std::uint32_t second_vertex_base) {
  assert(trees.begin.size() == 3 && trees.begin[2] == grid.corners.size());
  const std::size_t n = grid.corners.size();
  CombinedBroadPhase found;
  // Surfaces that do not crowd each other, or operands' trees that do not
  // merge (keyed over cells of their own): the separate searches cost less,
  // and run exactly as without this step (it prepares nothing for them).
  if (trees.tree[0].key_bounds() != trees.tree[1].key_bounds() || !crowded(grid, trees)) {
    add_diagonals(trees, grid.corners);
    return found;
  }
  found.prepared = FillVector<ContactTriangle>(n);  // every entry written below
  const auto prepare = [&](std::size_t o) {
    std::vector<std::uint32_t> members(trees.begin[o + 1] - trees.begin[o]);
    std::iota(members.begin(), members.end(), trees.begin[o]);
    const std::span<ContactTriangle> own = std::span<ContactTriangle>(found.prepared).subspan(trees.begin[o], members.size());
    prepare_contact_triangles(grid, members, own, searched[o]);
    if (o == 1)
      for (ContactTriangle& t : own)
        for (std::uint32_t& id : t.id) id += second_vertex_base;
  };
  // The stars and the frames' samples side by side: where a frame is found
  // the separate searches run after this, which used to overlap them.
  bool framed = false;
  tbb::parallel_invoke([&] { prepare(0); }, [&] { prepare(1); },
                       [&] { framed = sample_frames(grid, trees, searched); });
  const std::span<const ContactTriangle> tris = found.prepared;
  // The separate searches, which run instead, read the operands' diagonals.
  const auto declined = [&] {
    add_diagonals(trees, grid.corners);
    return std::move(found);
  };
  if (framed) return declined();  // a filter the tree over both would lack
  // One tree over both: the operands' orders merged (their cells agree).
  const TriangleTree all = TriangleTree::merged(trees.tree[0], trees.tree[1]);
  const LeafDiagonals diagonals(all, tris);
  std::vector<std::uint8_t> second;
  static_assert(TriangleTree::kLeaf <= 8, "one byte of slot bits per leaf");
  all.fill_leaf_blocks(second, [&](std::uint8_t& bits, std::size_t s, std::uint32_t item) {
    if (s == 0) bits = 0;
    if (item != TriangleTree::kNoItem && item >= trees.begin[1]) bits = static_cast<std::uint8_t>(bits | 1u << s);
  });
  MeetingPairs meetings;
  MixedOperands mixed;
  mixed.second = second;
  mixed.searched = searched;
  mixed.budget = kCountingPerTriangle * n + (std::size_t{1} << 16);
  mixed.meetings = &meetings;
  if (!find_contacts_and_meetings(tris, all, diagonals, mixed)) return declined();
  found.partners = partners_from(meetings, n);
  found.prepared = {};
  return found;
}

}  // namespace ember::core
