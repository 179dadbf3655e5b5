#pragma once
// A set of output vertices bucketed by rounded position, for the mesh
// stage's exact searches of vertices on a segment (T-junctions, diagonals).

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <optional>
#include <span>
#include <utility>
#include <vector>

#include "core/support/principal_frame.hpp"
#include "core/support/sort_pairs.hpp"
#include "ember/mesh.hpp"

namespace ember::core {

/// A floating-point filter for the exact on-segment tests that follow a
/// search: true only if the exact point whose correctly rounded position is
/// rv cannot lie on the exact segment whose end points round to ra and rb.
///
/// Why it is sound: let M be the largest |coordinate| of the three and D the
/// largest |rb - ra| coordinate. Correct rounding moves each coordinate by at
/// most 2^-53 M (normal range, ensured below). If the exact point is
/// a + t (b - a), then rv - ra = t (rb - ra) + e with |e_i| <= 2^-51 M, so each
/// component of (rb - ra) x (rv - ra) = (rb - ra) x e is at most
/// 2 D 2^-51 M = 2^-50 D M; evaluating it in double (two correctly rounded
/// differences per factor, two products, one difference, |rv - ra| <= 2M)
/// adds less than 2^-48 D M. A component above 2^-40 D M therefore rules the
/// point out, with a margin of 2^7. Outside 2^-400 <= D, M <= 2^400 (where
/// subnormals or overflow could spoil the bounds) it rules nothing out.
///
/// SegmentFilter(ra, rb).clearly_off(rv) computes what depends on ra and rb
/// alone once for many candidates rv (the T-junction search tests hundreds
/// per edge in a pile of slivers, and that part is a large share of the
/// filter's cost); clearly_off_segment(ra, rb, rv) is the one-off form.
class SegmentFilter {
 public:
  SegmentFilter(const Vec3d& ra, const Vec3d& rb)
      : ra_(ra),
        m_(std::max(
            {std::fabs(ra.x), std::fabs(ra.y), std::fabs(ra.z), std::fabs(rb.x), std::fabs(rb.y), std::fabs(rb.z)})),
        dx_(rb.x - ra.x),
        dy_(rb.y - ra.y),
        dz_(rb.z - ra.z) {
    const double D = std::max({std::fabs(dx_), std::fabs(dy_), std::fabs(dz_)});
    usable_ = D >= 0x1p-400;
    scaled_d_ = 0x1p-40 * D;
  }
  bool clearly_off(const Vec3d& rv) const {
    const double M = std::max({m_, std::fabs(rv.x), std::fabs(rv.y), std::fabs(rv.z)});
    if (!usable_ || !(M <= 0x1p400)) return false;
    const double wx = rv.x - ra_.x, wy = rv.y - ra_.y, wz = rv.z - ra_.z;
    const double bound = scaled_d_ * M;
    return std::fabs(dy_ * wz - dz_ * wy) > bound || std::fabs(dz_ * wx - dx_ * wz) > bound ||
           std::fabs(dx_ * wy - dy_ * wx) > bound;
  }

 private:
  Vec3d ra_;
  double m_, dx_, dy_, dz_, scaled_d_ = 0;
  bool usable_ = false;
};

inline bool clearly_off_segment(const Vec3d& ra, const Vec3d& rb, const Vec3d& rv) {
  return SegmentFilter(ra, rb).clearly_off(rv);
}

/// A conservative box test for the segment searches below: false only if no
/// box point can be the correctly rounded position of an exact point on the
/// exact segment whose end points round to ra and rb.
///
/// Why it is sound (M, the largest |coordinate| of ra and rb, bounds the
/// coordinates of such positions, which lie in the box of ra and rb):
/// clearly_off_segment's bound puts such a position rv within 2^-51 M, per
/// coordinate, of ra + t (rb - ra) for some t in [0, 1]. The test clips that
/// segment's parameter range to the box grown by pad = 2^-40 M, slab by slab;
/// each computed slab bound (one rounded difference for rb - ra, one for the
/// grown face, one for its distance from ra, a rounded reciprocal and a
/// product) is off by less than 2^-48 M in position, so the computed range
/// contains the exact range of the box grown by 2^-40 M - 2^-48 M > 2^-51 M,
/// which contains t. Outside 2^-400 <= M <= 2^400 it rules nothing out.
class SegmentTube {
 public:
  /// With `pad` (at least 2^-40 M): the box grown by pad instead, for
  /// positions within pad - 2^-48 M of the segment (VertexIndex's frame).
  SegmentTube(const Vec3d& ra, const Vec3d& rb, double pad = 0) {
    const double m = std::max(
        {std::fabs(ra.x), std::fabs(ra.y), std::fabs(ra.z), std::fabs(rb.x), std::fabs(rb.y), std::fabs(rb.z)});
    usable_ = m >= 0x1p-400 && m <= 0x1p400;
    pad_ = std::max(0x1p-40 * m, pad);
    start_ = {ra.x, ra.y, ra.z};
    const std::array<double, 3> d{rb.x - ra.x, rb.y - ra.y, rb.z - ra.z};
    for (int a = 0; a < 3; ++a) inverse_[a] = d[a] == 0 ? 0 : 1 / d[a];
  }

  /// False only if [lo, hi] holds no such position (see above).
  bool meets(const Vec3d& lo, const Vec3d& hi) const {
    if (!usable_) return true;
    const std::array<double, 3> l{lo.x, lo.y, lo.z}, h{hi.x, hi.y, hi.z};
    double t0 = 0, t1 = 1;
    for (int a = 0; a < 3; ++a) {
      const double from = l[a] - pad_, to = h[a] + pad_;
      if (inverse_[a] == 0) {  // rb - ra is 0 in this coordinate: the segment stays at ra's
        if (start_[a] < from || start_[a] > to) return false;
        continue;
      }
      double u = (from - start_[a]) * inverse_[a], v = (to - start_[a]) * inverse_[a];
      if (u > v) std::swap(u, v);
      t0 = std::max(t0, u);
      t1 = std::min(t1, v);
    }
    return t0 <= t1;
  }

 private:
  std::array<double, 3> start_{}, inverse_{};
  double pad_ = 0;
  bool usable_ = false;
};

/// A set of vertices bucketed in a uniform grid over their rounded positions
/// (cells about one mean edge long, found through a hash table). Positions
/// are copied so that a query touches only the set's own memory.
///
/// Members may carry a class 0, 1 or 2 (member_class[i] for members[i]);
/// within a cell they are ordered by class, and each part keeps its own
/// bounds, so a query can visit classes 0-1 (Part::kLow) or 1-2
/// (Part::kHigh) alone at no extra cost (the T-junction search's "vertices
/// of the other operand": tjunctions.cpp).
///
/// Cells one mean edge long can hold whole clusters of vertices: where the
/// edges are long slivers (thousands of units long, 1e-3 wide), a cell holds
/// the thousands of vertices across a rod's end, and every edge passing it
/// would test them all. A cell with
/// more than kTreeMembers members therefore keeps them in a small kd-tree,
/// and a segment query descends only into the nodes whose boxes the segment
/// passes (SegmentTube), testing the classes member by member there.
///
/// Cells and trees are laid out in the principal frame of the members'
/// positions (principal_frame.hpp), not along the axes: a pile of diagonal
/// slivers (rods thousands of units long and far narrower) puts the whole
/// section of a rod into the axis-aligned box of every stretch of a strip's
/// edge, so the T-junction search would filter thousands of vertices per
/// long edge, nearly all of which the filter rejects; in the frame the boxes
/// of such a stretch are thin across the rod.
///
/// Why the frame is sound: the frame R (orthonormal rows, |R_kj| <= 1) is
/// taken as an exact linear map. Let M be the larger |coordinate| of the
/// query's rounded end points ra and rb. A point p exactly on the segment
/// a-b lies in the box of a and b and rounds to rv with |rv - p| <= 2^-53 M
/// per coordinate, so R rv lies within 3 * 2^-53 M of R p, and R p within
/// 3 * 2^-53 M of the exact segment from R ra to R rb (a convex combination
/// of the end points' rounding errors). Each computed frame coordinate (three
/// products and two sums of terms below M) errs by less than 2^-50 * 3 M.
/// So a member on the segment lies within 2^-46 M of the segment between the
/// computed frame positions of ra and rb, and the query pads everything by
/// 2^-40 M: the end points' box, each piece's box and the crowded cells'
/// tube. (At most 2^-1000 more, so that subnormal roundings are covered;
/// members beyond 2^1000 keep the axes, where R is the identity and every
/// frame coordinate exact.)
class VertexIndex {
 public:
  enum class Part { kAll, kLow, kHigh };

  VertexIndex(const std::vector<Vec3d>& all, std::vector<std::uint32_t> members, double mean_edge,
              std::span<const std::uint8_t> member_class = {})
      : ids_(std::move(members)) {
    if (ids_.empty()) return;
    pos_.resize(ids_.size());
    choose_frame(all);
    for (std::size_t i = 0; i < ids_.size(); ++i) pos_[i] = to_frame(all[ids_[i]]);
    lo_ = hi_ = pos_[0];
    for (const Vec3d& p : pos_) {
      lo_ = {std::min(lo_.x, p.x), std::min(lo_.y, p.y), std::min(lo_.z, p.z)};
      hi_ = {std::max(hi_.x, p.x), std::max(hi_.y, p.y), std::max(hi_.z, p.z)};
    }
    // Each part's own bounds (a query far from a part's members stops at once).
    for (std::size_t i = 0; i < pos_.size(); ++i) {
      const std::uint32_t c = class_of(member_class, i);
      for (const Part part : {Part::kLow, Part::kHigh}) {
        if (part == Part::kLow ? c > 1 : c < 1) continue;
        Bounds& b = bounds_[static_cast<int>(part)];
        b.lo = {std::min(b.lo.x, pos_[i].x), std::min(b.lo.y, pos_[i].y), std::min(b.lo.z, pos_[i].z)};
        b.hi = {std::max(b.hi.x, pos_[i].x), std::max(b.hi.y, pos_[i].y), std::max(b.hi.z, pos_[i].z)};
      }
    }
    bounds_[static_cast<int>(Part::kAll)] = {lo_, hi_};
    const double extent = std::max({hi_.x - lo_.x, hi_.y - lo_.y, hi_.z - lo_.z});
    cell_ = std::max(mean_edge, extent * 0x1p-20);
    if (!(cell_ > 0) || !std::isfinite(cell_)) cell_ = 1;
    inverse_cell_ = 1 / cell_;
    if (!std::isfinite(inverse_cell_)) inverse_cell_ = 0x1p1000;  // a subnormal cell: cells clamp to the grid's edge
    const auto n = static_cast<std::uint32_t>(pos_.size());
    FillVector<std::pair<std::uint64_t, std::uint32_t>> cells(n);  // (cell key << 2 | class, member), sorted
    // Sort key: the cell (60 bits), then the class (2 bits).
    for (std::uint32_t i = 0; i < n; ++i) cells[i] = {key(cell_of(pos_[i])) << 2 | class_of(member_class, i), i};
    sort_pairs(cells);
    // Members in cell order, so that a query scans its cells' positions and
    // ids contiguously (one indirection less per candidate, and cache lines
    // that hold neighbours).
    std::vector<Vec3d> by_cell_pos(n);
    std::vector<std::uint32_t> by_cell_id(n);
    class_.resize(n);
    for (std::uint32_t i = 0; i < n; ++i) {
      by_cell_pos[i] = pos_[cells[i].second];
      by_cell_id[i] = ids_[cells[i].second];
      class_[i] = static_cast<std::uint8_t>(cells[i].first & 3);
    }
    pos_ = std::move(by_cell_pos);
    ids_ = std::move(by_cell_id);
    // Open-addressing table: occupied cell key -> its run of members.
    std::size_t runs = 0;
    for (std::size_t i = 0; i < n; ++i) runs += i == 0 || cells[i].first >> 2 != cells[i - 1].first >> 2;
    std::size_t size = 16;
    while (size < 2 * runs) size *= 2;
    slots_.assign(size, Slot{});
    for (std::uint32_t i = 0; i < n;) {
      const std::uint64_t cell = cells[i].first >> 2;
      Slot slot{cell, i, i, i, i};
      while (slot.end < n && cells[slot.end].first >> 2 == cell) {
        const auto c = static_cast<std::uint32_t>(cells[slot.end].first & 3);
        ++slot.end;
        if (c < 1) slot.class1 = slot.end;
        if (c < 2) slot.class2 = slot.end;
      }
      if (slot.end - slot.begin > kTreeMembers) slot.tree = build_tree(slot.begin, slot.end);
      std::size_t h = hash(cell) & (size - 1);
      while (slots_[h].end != 0) h = (h + 1) & (size - 1);
      slots_[h] = slot;
      i = slot.end;
    }
  }

  /// Calls f(v) for every member whose frame position lies near the segment
  /// between the rounded end points world_a and world_b (their frame
  /// positions): within 2^-40 of their largest |coordinate|, where every
  /// exact point of the segment a-b rounds to (class comment). Long edges are
  /// cut into pieces about one cell long, each covering its stretch of the
  /// segment with that pad, so a long edge visits the cells along it rather
  /// than its whole box. A member near two pieces may be reported twice; some
  /// that are not near are reported too (callers filter them).
  template <typename F>
  void for_each_near_segment(const Vec3d& world_a, const Vec3d& world_b, F&& f, Part part = Part::kAll) const {
    // See the class comment for why pad covers the frame's rounding.
    const double pad = std::max(0x1p-40 * std::max({std::fabs(world_a.x), std::fabs(world_a.y), std::fabs(world_a.z),
                                                    std::fabs(world_b.x), std::fabs(world_b.y), std::fabs(world_b.z)}),
                                0x1p-1000);
    const Vec3d ra = to_frame(world_a), rb = to_frame(world_b);
    const Vec3d lo{std::min(ra.x, rb.x) - pad, std::min(ra.y, rb.y) - pad, std::min(ra.z, rb.z) - pad};
    const Vec3d hi{std::max(ra.x, rb.x) + pad, std::max(ra.y, rb.y) + pad, std::max(ra.z, rb.z) + pad};
    const double span = std::max({hi.x - lo.x, hi.y - lo.y, hi.z - lo.z});
    const double pieces = std::min(std::ceil(span / cell_), 65536.0);
    std::optional<SegmentTube> tube;  // only crowded cells use it
    if (!nodes_.empty()) tube.emplace(ra, rb, pad);
    const SegmentTube* const near = tube ? &*tube : nullptr;
    if (!(pieces > 2)) return for_each_in_box(lo, hi, f, part, near);
    const auto n = static_cast<int>(pieces);
    auto at = [&](int i) {
      const double t = static_cast<double>(i) / n;
      return Vec3d{ra.x + (rb.x - ra.x) * t, ra.y + (rb.y - ra.y) * t, ra.z + (rb.z - ra.z) * t};
    };
    Vec3d p0 = ra;
    for (int i = 1; i <= n; ++i) {
      const Vec3d p1 = i == n ? rb : at(i);
      const Vec3d l{std::max(lo.x, std::min(p0.x, p1.x) - pad), std::max(lo.y, std::min(p0.y, p1.y) - pad),
                    std::max(lo.z, std::min(p0.z, p1.z) - pad)};
      const Vec3d h{std::min(hi.x, std::max(p0.x, p1.x) + pad), std::min(hi.y, std::max(p0.y, p1.y) + pad),
                    std::min(hi.z, std::max(p0.z, p1.z) + pad)};
      for_each_in_box(l, h, f, part, near);
      p0 = p1;
    }
  }

 private:
  /// Calls f(v) for every member of `part` whose frame position lies in
  /// [lo, hi] (with a tube: in crowded cells, only where the tube meets the
  /// member's kd-tree leaf).
  template <typename F>
  void for_each_in_box(const Vec3d& lo, const Vec3d& hi, F&& f, Part part = Part::kAll,
                       const SegmentTube* tube = nullptr) const {
    const Bounds& b = bounds_[static_cast<int>(part)];
    if (pos_.empty() || hi.x < b.lo.x || hi.y < b.lo.y || hi.z < b.lo.z || lo.x > b.hi.x || lo.y > b.hi.y ||
        lo.z > b.hi.z)
      return;
    const std::array<std::int64_t, 3> c0 = cell_of(lo), c1 = cell_of(hi);
    auto inside = [&](std::uint32_t i) {  // i in cell order; no short-circuits: the outcomes follow no pattern
      const Vec3d& p = pos_[i];
      return (p.x >= lo.x) & (p.x <= hi.x) & (p.y >= lo.y) & (p.y <= hi.y) & (p.z >= lo.z) & (p.z <= hi.z);
    };
    for (std::int64_t x = c0[0]; x <= c1[0]; ++x)
      for (std::int64_t y = c0[1]; y <= c1[1]; ++y)
        for (std::int64_t z = c0[2]; z <= c1[2]; ++z) {
          const Slot& slot = find(key({x, y, z}));
          if (slot.tree != kNoTree) {
            visit_tree(slot.tree, lo, hi, tube, part, [&](std::uint32_t i) {
              if (inside(i)) f(ids_[i]);
            });
            continue;
          }
          const std::uint32_t begin = part == Part::kHigh ? slot.class1 : slot.begin;
          const std::uint32_t end = part == Part::kLow ? slot.class2 : slot.end;
          for (std::uint32_t i = begin; i < end; ++i)
            if (inside(i)) f(ids_[i]);
        }
  }

  /// The principal frame of the members' positions, or the axes where the
  /// positions are too large for its rounding bound (class comment) or do
  /// not spread.
  void choose_frame(const std::vector<Vec3d>& all) {
    double largest = 0;
    for (const std::uint32_t id : ids_)
      largest = std::max({largest, std::fabs(all[id].x), std::fabs(all[id].y), std::fabs(all[id].z)});
    if (!(largest >= 0x1p-1000 && largest <= 0x1p1000)) return;
    // Scaled to at most 1, so that the covariance neither underflows nor
    // overflows in tiny or huge units (any frame is sound; this one separates).
    const double scale = 1 / largest;
    std::vector<std::array<double, 3>> points(ids_.size());
    for (std::size_t i = 0; i < ids_.size(); ++i) {
      const Vec3d& p = all[ids_[i]];
      points[i] = {p.x * scale, p.y * scale, p.z * scale};
    }
    FrameAxes frame;
    if (principal_frame(points, frame)) frame_ = frame;
  }
  Vec3d to_frame(const Vec3d& p) const {
    const auto along = [&](const std::array<double, 3>& u) { return u[0] * p.x + u[1] * p.y + u[2] * p.z; };
    return {along(frame_[0]), along(frame_[1]), along(frame_[2])};
  }

  /// Monotone in each coordinate (floating subtraction and multiplication by
  /// a positive constant are monotone), so a box's cells bracket its points'.
  /// Clamped to [0, 2^20 - 1] first, where truncation is floor.
  std::array<std::int64_t, 3> cell_of(const Vec3d& p) const {
    auto c = [&](double x, double l) {
      return static_cast<std::int64_t>(std::clamp((x - l) * inverse_cell_, 0.0, double{(1 << 20) - 1}));
    };
    return {c(p.x, lo_.x), c(p.y, lo_.y), c(p.z, lo_.z)};
  }
  /// Members without a class belong to both parts (class 1), in the cell
  /// order and the bounds alike.
  static std::uint32_t class_of(std::span<const std::uint8_t> member_class, std::size_t i) {
    return member_class.empty() ? 1u : member_class[i];
  }
  static std::uint64_t key(const std::array<std::int64_t, 3>& c) {
    return (static_cast<std::uint64_t>(c[0]) << 42) | (static_cast<std::uint64_t>(c[1]) << 21) |
           static_cast<std::uint64_t>(c[2]);
  }

  /// A crowded cell's members in kd-tree order: node k covers members
  /// [begin, end) within the box [lo, hi]; children first_child and
  /// first_child + 1, none (a leaf) when first_child is 0.
  struct Node {
    Vec3d lo, hi;
    std::uint32_t begin = 0, end = 0, first_child = 0;
  };
  static constexpr std::uint32_t kTreeMembers = 64;  ///< cells with more members get a tree
  /// Members per leaf, at most: each one a leaf holds is box-tested and
  /// filtered, so small leaves pay; smaller ones than 4 gain little more.
  static constexpr std::uint32_t kTreeLeaf = 4;
  static constexpr std::uint32_t kNoTree = UINT32_MAX;

  /// Builds the tree of members [begin, end) (reordering them) and returns its root.
  std::uint32_t build_tree(std::uint32_t begin, std::uint32_t end) {
    const auto root = static_cast<std::uint32_t>(nodes_.size());
    nodes_.emplace_back();
    std::vector<std::uint32_t> order(end - begin);  // order[j]: the member that goes to begin + j
    for (std::uint32_t j = 0; j < order.size(); ++j) order[j] = begin + j;
    split(root, begin, order.data(), order.data() + order.size());
    const std::vector<Vec3d> pos(pos_.begin() + begin, pos_.begin() + end);
    const std::vector<std::uint32_t> ids(ids_.begin() + begin, ids_.begin() + end);
    const std::vector<std::uint8_t> cls(class_.begin() + begin, class_.begin() + end);
    for (std::uint32_t j = 0; j < order.size(); ++j) {
      pos_[begin + j] = pos[order[j] - begin];
      ids_[begin + j] = ids[order[j] - begin];
      class_[begin + j] = cls[order[j] - begin];
    }
    return root;
  }
  /// Node k over the members `first..last` (pointers into the build order,
  /// member slots from `begin`): their box, then halves at the median of
  /// the box's widest coordinate.
  void split(std::uint32_t k, std::uint32_t begin, std::uint32_t* first, std::uint32_t* last) {
    Node node;
    node.begin = begin;
    node.end = begin + static_cast<std::uint32_t>(last - first);
    node.lo = node.hi = pos_[*first];
    for (const std::uint32_t* i = first; i != last; ++i) {
      const Vec3d& p = pos_[*i];
      node.lo = {std::min(node.lo.x, p.x), std::min(node.lo.y, p.y), std::min(node.lo.z, p.z)};
      node.hi = {std::max(node.hi.x, p.x), std::max(node.hi.y, p.y), std::max(node.hi.z, p.z)};
    }
    if (node.end - node.begin > kTreeLeaf) {
      const double ex = node.hi.x - node.lo.x, ey = node.hi.y - node.lo.y, ez = node.hi.z - node.lo.z;
      const int axis = ex >= ey && ex >= ez ? 0 : ey >= ez ? 1 : 2;
      const auto coord = [&](std::uint32_t i) { return axis == 0 ? pos_[i].x : axis == 1 ? pos_[i].y : pos_[i].z; };
      std::uint32_t* mid = first + (last - first) / 2;
      std::nth_element(first, mid, last, [&](std::uint32_t a, std::uint32_t b) { return coord(a) < coord(b); });
      node.first_child = static_cast<std::uint32_t>(nodes_.size());
      nodes_.resize(nodes_.size() + 2);
      split(node.first_child, begin, first, mid);
      split(node.first_child + 1, begin + static_cast<std::uint32_t>(mid - first), mid, last);
    }
    nodes_[k] = node;
  }
  /// Calls g(i) for the members of `part` in the leaves of tree `root` whose
  /// boxes meet [lo, hi] and the tube (if any).
  template <typename G>
  void visit_tree(std::uint32_t root, const Vec3d& lo, const Vec3d& hi, const SegmentTube* tube, Part part,
                  G&& g) const {
    std::uint32_t stack[64];  // depth <= log2(2^32 / kTreeLeaf) + 1 < 32; two entries per level
    int top = 0;
    stack[top++] = root;
    while (top > 0) {
      const Node& n = nodes_[stack[--top]];
      if (n.hi.x < lo.x || n.hi.y < lo.y || n.hi.z < lo.z || n.lo.x > hi.x || n.lo.y > hi.y || n.lo.z > hi.z) continue;
      if (tube && !tube->meets(n.lo, n.hi)) continue;
      if (n.first_child != 0) {
        stack[top++] = n.first_child;
        stack[top++] = n.first_child + 1;
        continue;
      }
      for (std::uint32_t i = n.begin; i < n.end; ++i)
        if ((part != Part::kLow || class_[i] <= 1) && (part != Part::kHigh || class_[i] >= 1)) g(i);
    }
  }

  FrameAxes frame_{{{1, 0, 0}, {0, 1, 0}, {0, 0, 1}}};  ///< rows: the frame's axes in world coordinates
  std::vector<Node> nodes_;
  std::vector<std::uint8_t> class_;  ///< per member (cell order): its class
  std::vector<std::uint32_t> ids_;   ///< member i is output vertex ids_[i] (in cell order once built)
  std::vector<Vec3d> pos_;           ///< its rounded position in the frame (to_frame)
  Vec3d lo_{}, hi_{};
  struct Bounds {  ///< empty: lo > hi
    Vec3d lo{HUGE_VAL, HUGE_VAL, HUGE_VAL}, hi{-HUGE_VAL, -HUGE_VAL, -HUGE_VAL};
  };
  std::array<Bounds, 3> bounds_{};  ///< by Part
  double cell_ = 1, inverse_cell_ = 1;
  struct Slot {
    std::uint64_t key = 0;
    std::uint32_t begin = 0, end = 0;      ///< run of members (cell order); end == 0: empty slot
    std::uint32_t class1 = 0, class2 = 0;  ///< where classes 1 and 2 begin in the run (no tree)
    std::uint32_t tree = kNoTree;          ///< a crowded cell's kd-tree root (its run in tree order)
  };
  std::vector<Slot> slots_;
  static std::uint64_t hash(std::uint64_t k) { return (k ^ (k >> 29)) * 0x9E3779B97F4A7C15ull >> 20; }
  const Slot& find(std::uint64_t k) const {
    static constexpr Slot kEmpty{};
    for (std::size_t h = hash(k) & (slots_.size() - 1);; h = (h + 1) & (slots_.size() - 1)) {
      if (slots_[h].end == 0) return kEmpty;
      if (slots_[h].key == k) return slots_[h];
    }
  }
};

}  // namespace ember::core
