// One broad phase for the proof and the solid path (combined_search.hpp).
#include "core/combined_search.hpp"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_invoke.h>

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

/// box_of every triangle, in parallel.
std::vector<Box32> boxes_of(std::span<const std::array<IntPoint, 3>> corners) {
  std::vector<Box32> boxes(corners.size());
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, corners.size(), 4096),
                    [&](const tbb::blocked_range<std::size_t>& r) {
                      for (std::size_t i = r.begin(); i != r.end(); ++i) boxes[i] = box_of(corners[i]);
                    });
  return boxes;
}

}  // namespace

CombinedBroadPhase combined_broad_phase(const GridTriangles& grid, OperandTrees& trees, std::array<bool, 2> searched,
                                        std::uint32_t second_vertex_base) {
  assert(trees.begin.size() == 3 && trees.begin[2] == grid.corners.size());
  const std::size_t n = grid.corners.size();
  CombinedBroadPhase found;
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
  if (framed) return declined();
  // One tree over both: the operands' orders merged where their cells agree
  // (build_operand_trees' common_cells), else sorted anew.
  const TriangleTree all = trees.tree[0].key_bounds() == trees.tree[1].key_bounds()
                               ? TriangleTree::merged(trees.tree[0], trees.tree[1])
                               : TriangleTree(boxes_of(grid.corners));
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
