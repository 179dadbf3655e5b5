// Adaptive subdivision (paper Section 4.2): split the box at an integer
// position, clip every polygon into the children and carry a reference point
// with a known winding-number vector into each child.
#include "core/route/general/subdivide.hpp"

#include <tbb/parallel_for.h>
#include <tbb/task_group.h>

#include <algorithm>
#include <cmath>
#include <iterator>

#include "core/model/output_polygon.hpp"
#include "core/model/solve_context.hpp"
#include "core/route/general/subproblem.hpp"
#include "core/route/general/leaf.hpp"
#include "core/route/shared/trace.hpp"
#include "ember/error.hpp"

namespace ember::core {

namespace {

/// Per operand present in a subproblem: how many polygons, their bounding
/// box, and (filled by choose_split) the centroid sample. One pass over the
/// soup serves the early-outs and the split choice.
struct OperandSummary {
  std::array<double, 3> lo{HUGE_VAL, HUGE_VAL, HUGE_VAL}, hi{-HUGE_VAL, -HUGE_VAL, -HUGE_VAL}, sum{};
  std::size_t count = 0, sampled = 0;
};
struct SoupSummary {
  std::vector<OperandSummary> ops;     ///< indexed by operand
  std::vector<std::uint32_t> present;  ///< operands with polygons, in order of first appearance
};

SoupSummary summarize(const Soup& soup, std::size_t operands) {
  SoupSummary sum;
  sum.ops.resize(operands);
  for (const SoupPolygon& p : soup) {
    OperandSummary& s = sum.ops[p.operand];
    if (s.count++ == 0) sum.present.push_back(p.operand);
    for (int a = 0; a < 3; ++a) {
      s.lo[a] = std::min(s.lo[a], p.lo[a]);
      s.hi[a] = std::max(s.hi[a], p.hi[a]);
    }
  }
  return sum;
}

/// The axis to split and the position, or -1 when the box cannot be split
/// (a split position must lie strictly inside, so the extent must be >= 2).
///
/// Section 4.5.3: the soup's operands are summarized by their bounding boxes
/// and centroids (of up to kSample polygon box centres). A face of operand
/// j's box that separates operand i's centroid from all of j is a candidate:
/// one side of it holds no polygon of j, so the early terminations get a
/// chance there. The candidate farthest from the centroid wins; without one,
/// the longest axis is halved (the paper's baseline).
int choose_split(const Subproblem& pb, SoupSummary& summary, std::int64_t& position) {
  const Box& box = pb.box;
  std::vector<OperandSummary>& ops = summary.ops;
  const std::vector<std::uint32_t>& present = summary.present;
  if (present.size() > 1) {
    // Centroids from a deterministic subset (every k-th polygon).
    constexpr std::size_t kSample = 64;
    const std::size_t step = std::max<std::size_t>(1, pb.soup.size() / kSample);
    for (std::size_t n = 0; n < pb.soup.size(); n += step) {
      const SoupPolygon& p = pb.soup[n];
      OperandSummary& s = ops[p.operand];
      for (int a = 0; a < 3; ++a) s.sum[a] += 0.5 * (p.lo[a] + p.hi[a]);
      ++s.sampled;
    }
    int best_axis = -1;
    double best_distance = 0;
    for (const std::uint32_t i : present) {
      if (ops[i].sampled == 0) continue;
      for (const std::uint32_t j : present) {
        if (i == j) continue;
        for (int a = 0; a < 3; ++a) {
          const double c = ops[i].sum[a] / static_cast<double>(ops[i].sampled);
          // The integer plane just outside j's box on the side of c.
          std::int64_t pos;
          if (c < ops[j].lo[a]) {
            pos = static_cast<std::int64_t>(std::floor(ops[j].lo[a]));
          } else if (c > ops[j].hi[a]) {
            pos = static_cast<std::int64_t>(std::ceil(ops[j].hi[a]));
          } else {
            continue;
          }
          if (pos <= box.lo[a] || pos >= box.hi[a]) continue;
          const double distance = std::fabs(c - static_cast<double>(pos));
          if (distance > best_distance) {
            best_distance = distance;
            best_axis = a;
            position = pos;
          }
        }
      }
    }
    if (best_axis >= 0) return best_axis;
  }
  int axis = -1;
  std::int64_t best = 1;
  for (int a = 0; a < 3; ++a) {
    const std::int64_t extent = box.hi[a] - box.lo[a];
    if (extent > best) {
      best = extent;
      axis = a;
    }
  }
  if (axis >= 0) position = box.lo[axis] + (box.hi[axis] - box.lo[axis]) / 2;
  return axis;
}

/// A new reference point strictly inside the child that does not contain
/// `ref`: first the projection across the split plane, nudged inside by a
/// dyadic fraction (one axis-parallel segment); then paths that also move the
/// other coordinates. Each candidate is validated by an exact trace in the
/// parent, whose soup contains every polygon the path can meet.
bool move_reference(const Subproblem& parent, const Box& child, int axis, std::int64_t split, Dyadic& ref, Wnv& w) {
  const bool upper = child.lo[axis] == split;  // child lies above the split plane
  // Offsets of odd/128 grid units: "generic" positions. Half-integers would be
  // a poor choice: edges between grid points pass through them.
  constexpr int kShift = 7;
  constexpr std::int64_t kOdd[] = {45, 83, 19, 109, 67, 31, 97, 53};
  for (const std::int64_t odd : kOdd) {
    const int shift = std::max(kShift, parent.ref.shift);
    Dyadic cand = with_shift(parent.ref, shift);
    const std::int64_t offset = odd << (shift - kShift);
    cand.num[axis] = static_cast<__int128>(split) * (std::int64_t{1} << shift) + (upper ? offset : -offset);
    Wnv trial = parent.ref_w;
    if (trace_axis_segment(parent.soup, with_shift(parent.ref, shift), cand, axis, trial)) {
      ref = cand;
      w = std::move(trial);
      return true;
    }
  }
  // Rare: the line through the projection meets an edge. Move the other two
  // coordinates by small dyadic amounts first (off that line), staying
  // strictly inside, then cross the split plane.
  const int b = (axis + 1) % 3, c = (axis + 2) % 3;
  for (int s = 3; s <= 12; ++s) {
    for (int variant = 0; variant < 8; ++variant) {
      const int shift = std::max(s + 2, parent.ref.shift);
      Dyadic cand = with_shift(parent.ref, shift);
      const std::int64_t unit = std::int64_t{1} << (shift - s);
      // 1/2 ± 2^-s of a grid unit past the split plane: strictly inside the child.
      cand.num[axis] = static_cast<__int128>(split) * (std::int64_t{1} << shift) +
                       (upper ? 1 : -1) * ((std::int64_t{1} << (shift - 1)) + unit * (variant % 3 - 1));
      cand.num[b] += ((variant & 1) ? unit : -unit) * (1 + variant / 2);
      cand.num[c] += ((variant & 2) ? unit : -unit) * (1 + variant / 4);
      bool inside = true;
      for (const int a : {b, c}) inside &= compare(cand, a, child.lo[a]) > 0 && compare(cand, a, child.hi[a]) < 0;
      if (!inside) continue;
      Wnv trial = parent.ref_w;
      if (trace_path(parent.soup, parent.ref, cand, {b, c, axis}, trial)) {
        ref = cand;
        w = std::move(trial);
        return true;
      }
    }
  }
  return false;
}

/// Clips soup[begin, end) into left/right, keeping the soup's order.
void split_range(Soup& soup, std::size_t begin, std::size_t end, int axis, std::int64_t position, Soup& left,
                 Soup& right) {
  const Plane plane = axis_plane(axis, position);
  Polygon neg, pos;
  left.reserve(left.size() + (end - begin) / 2 + 8);
  right.reserve(right.size() + (end - begin) / 2 + 8);
  for (std::size_t i = begin; i < end; ++i) {
    SoupPolygon& p = soup[i];
    // Cheap exact-enough rejection: the box is conservative.
    if (p.hi[axis] < static_cast<double>(position)) {
      left.push_back(std::move(p));
      continue;
    }
    if (p.lo[axis] > static_cast<double>(position)) {
      right.push_back(std::move(p));
      continue;
    }
    // An unbuilt triangle is sided by its integer corners (clip's exact
    // classification of them) and built only when the plane cuts it.
    if (unbuilt(p)) {
      int below = 0, above = 0;
      for (const IntPoint& c : *p.corners) {
        const std::int64_t x = axis == 0 ? c.x : (axis == 1 ? c.y : c.z);
        below += x < position;
        above += x > position;
      }
      if (above == 0) {  // Negative or On: polygons in the plane go to the lower child only
        left.push_back(std::move(p));
        continue;
      }
      if (below == 0) {
        right.push_back(std::move(p));
        continue;
      }
      materialize(p);
    }
    switch (clip(*p.poly, plane, neg, pos)) {
      case ClipSide::Negative:
      case ClipSide::On:  // polygons in the plane go to the lower child only
        left.push_back(std::move(p));
        break;
      case ClipSide::Positive: right.push_back(std::move(p)); break;
      case ClipSide::Both: {
        // The parts take over the clip buffers; the old polygon's buffers
        // become the next clip's, so a split costs one allocation, not four.
        SoupPolygon r{std::make_unique<Polygon>(std::move(pos)), p.id, p.operand, {}, {}, 0, p.corners};
        pos = Polygon{};
        p.splits = r.splits = p.splits == 255 ? p.splits : static_cast<std::uint8_t>(p.splits + 1);
        std::swap(*p.poly, neg);
        update_bounds(p);
        update_bounds(r);
        left.push_back(std::move(p));
        right.push_back(std::move(r));
        break;
      }
    }
  }
}

/// Splits the soup at the plane. Large soups (the first levels, before the
/// recursion has made enough tasks for all threads) are clipped in parallel
/// chunks that are concatenated in soup order, so the result is the same for
/// any thread count.
void split_soup(Soup&& soup, int axis, std::int64_t position, Soup& left, Soup& right) {
  constexpr std::size_t kChunk = 2048;
  if (soup.size() < 2 * kChunk) {
    split_range(soup, 0, soup.size(), axis, position, left, right);
    return;
  }
  const std::size_t chunks = (soup.size() + kChunk - 1) / kChunk;
  std::vector<Soup> lefts(chunks), rights(chunks);
  tbb::parallel_for(std::size_t{0}, chunks, [&](std::size_t c) {
    split_range(soup, c * kChunk, std::min(soup.size(), (c + 1) * kChunk), axis, position, lefts[c], rights[c]);
  });
  std::size_t nl = 0, nr = 0;
  for (std::size_t c = 0; c < chunks; ++c) {
    nl += lefts[c].size();
    nr += rights[c].size();
  }
  left.reserve(nl);
  right.reserve(nr);
  for (std::size_t c = 0; c < chunks; ++c) {
    std::move(lefts[c].begin(), lefts[c].end(), std::back_inserter(left));
    std::move(rights[c].begin(), rights[c].end(), std::back_inserter(right));
  }
}

}  // namespace

OutputPolygon whole_piece_output(const SoupPolygon& p, const Crossing& crossing) {
  OutputPolygon out;
  out.corners = p.corners;
  out.id = p.id;
  out.operand = p.operand;
  out.flip = crossing.flip;
  out.layer_lo = crossing.lo;
  out.layer_hi = crossing.hi;
  out.whole_piece = true;
  out.splits = p.splits;
  if (p.splits > 0) out.path = 0;  // the subproblem's own path (solve() numbers them)
  return out;
}

namespace {

/// Fig. 11 with a solid operand: if every polygon belongs to one solid
/// operand o, each has w_o = 0 in front and 1 behind, and all other winding
/// numbers equal the reference point's (nothing else is in the box), so all
/// polygons share one classification and no trace is needed.
bool emit_single_solid(Subproblem& pb, const SolveContext& ctx, const SoupSummary& summary,
                       std::vector<OutputPolygon>& out) {
  if (summary.present.size() != 1) return false;
  const std::uint32_t o = summary.present.front();
  if (!ctx.solid[o]) return false;
  Wnv front = pb.ref_w, back = pb.ref_w;
  front[o] = 0;
  back[o] = 1;
  const Crossing c = ctx.crossing(front, back);
  if (!c.emitted) return true;
  out.reserve(pb.soup.size());
  for (const SoupPolygon& p : pb.soup) out.push_back(whole_piece_output(p, c));
  return true;
}

}  // namespace

namespace {
/// indicator_constant for a subproblem whose operands with polygons are `present`:
/// the other operands keep the reference point's flags, the present ones are free.
bool indicator_constant(const Subproblem& pb, const SolveContext& ctx, const std::vector<std::uint32_t>& present) {
  if (ctx.expression) {
    std::vector<signed char> state(ctx.operands);
    for (std::size_t i = 0; i < ctx.operands; ++i) state[i] = pb.ref_w[i] != 0 ? 1 : 0;
    for (const std::uint32_t o : present) state[o] = -1;
    return ctx.expression->value_over(state) >= 0;
  }
  if (!ctx.op) return false;
  std::size_t inside = 0;
  for (std::size_t i = 0; i < ctx.operands; ++i) inside += pb.ref_w[i] != 0;
  bool first_present = false;
  for (const std::uint32_t o : present) {
    inside -= pb.ref_w[o] != 0;
    first_present |= o == 0;
  }
  const int first = first_present ? -1 : (pb.ref_w[0] != 0 ? 1 : 0);
  return ctx.over_free(inside, present.size(), first) >= 0;
}
}  // namespace

bool indicator_constant(const Subproblem& pb, const SolveContext& ctx) {
  return indicator_constant(pb, ctx, summarize(pb.soup, ctx.operands).present);
}

bool split_pays(std::size_t polygons, std::size_t straddling) {
  using u128 = unsigned __int128;  // exact for s <= n < 2^63: (n + s)^2 < 2^128
  const u128 n = polygons, both = n + straddling;
  return both * both < 2 * n * n;
}

namespace {

/// Output chunks in deterministic order: each leaf (or single-solid box)
/// fills one chunk, and parents concatenate their children's chunk lists, so
/// a polygon moves once (when flattened), not once per level. A chunk keeps
/// the path of the box that emitted it, for its path pieces.
struct OutputChunk {
  SplitPath path;
  std::vector<OutputPolygon> polys;
};
using OutputChunks = std::vector<OutputChunk>;

void solve_into(Subproblem&& pb, const SolveContext& ctx, OutputChunks& chunks) {
  if (pb.soup.empty()) return;
  SoupSummary summary = summarize(pb.soup, ctx.operands);
  if (indicator_constant(pb, ctx, summary.present)) return;
  std::vector<OutputPolygon> out;
  if (emit_single_solid(pb, ctx, summary, out)) {
    if (!out.empty()) chunks.push_back({pb.path, std::move(out)});
    return;
  }
  std::int64_t position = 0;
  int axis = pb.soup.size() > ctx.leaf_size ? choose_split(pb, summary, position) : -1;
  if (axis >= 0) {
    // A split that leaves many polygons in both children (a pile that no
    // plane separates) multiplies pieces without progress: solve the pile as
    // one leaf instead (split_pays).
    std::size_t straddling = 0;
    for (const SoupPolygon& p : pb.soup)
      straddling += p.lo[axis] < static_cast<double>(position) && p.hi[axis] > static_cast<double>(position);
    if (!split_pays(pb.soup.size(), straddling)) axis = -1;
  }
  if (axis < 0) {
    for (SoupPolygon& p : pb.soup) materialize(p);  // a leaf works on whole plane-based polygons
    solve_leaf(pb, ctx, out);
    if (!out.empty()) chunks.push_back({pb.path, std::move(out)});
    return;
  }
  Subproblem lower, upper;
  lower.box = upper.box = pb.box;
  lower.box.hi[axis] = position;
  upper.box.lo[axis] = position;
  lower.path = std::make_shared<const SplitStep>(SplitStep{pb.path, position, axis, false});
  upper.path = std::make_shared<const SplitStep>(SplitStep{pb.path, position, axis, true});
  // The reference point is strictly inside exactly one child (its coordinates
  // are never integers); the other child gets a new one.
  const bool ref_below = compare(pb.ref, axis, position) < 0;
  Subproblem& keeps = ref_below ? lower : upper;
  Subproblem& moves = ref_below ? upper : lower;
  keeps.ref = pb.ref;
  keeps.ref_w = pb.ref_w;
  if (!move_reference(pb, moves.box, axis, position, moves.ref, moves.ref_w))
    throw Error("ember: no valid reference path into a subproblem; the input is too degenerate for this version");
  split_soup(std::move(pb.soup), axis, position, lower.soup, upper.soup);
  pb.soup = Soup{};

  OutputChunks chunks_upper;
  tbb::task_group group;
  group.run([&] { solve_into(std::move(lower), ctx, chunks); });
  solve_into(std::move(upper), ctx, chunks_upper);
  group.wait();
  chunks.insert(chunks.end(), std::make_move_iterator(chunks_upper.begin()),
                std::make_move_iterator(chunks_upper.end()));
}

}  // namespace

SolveOutput solve(Subproblem&& pb, const SolveContext& ctx) {
  OutputChunks chunks;
  solve_into(std::move(pb), ctx, chunks);
  std::size_t total = 0;
  for (const auto& c : chunks) total += c.polys.size();
  SolveOutput out;
  out.polys.reserve(total);
  out.paths.reserve(chunks.size());
  for (auto& c : chunks) {
    // Path pieces name their chunk's path (they carry 0 until now).
    const auto k = static_cast<std::uint32_t>(out.paths.size());
    for (OutputPolygon& p : c.polys)
      if (p.path != OutputPolygon::kNoPath) p.path = k;
    out.paths.push_back(std::move(c.path));
    out.polys.insert(out.polys.end(), std::make_move_iterator(c.polys.begin()), std::make_move_iterator(c.polys.end()));
  }
  return out;
}

}  // namespace ember::core
