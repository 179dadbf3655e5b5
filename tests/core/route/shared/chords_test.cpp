// The leaf's chord filter (src/core/chords.hpp): it may only say "disjoint"
// when the two chords have no common point (checked against the exact
// line_region_nonempty over the chord constraints), including chords that
// touch at a point reached through an edge crossing, at coordinates up to
// the grid's limit; and it must decide most clearly separated pairs. The
// exact shortcut chords_separated_by_edge may only say "no overlap" when the
// exact line_region_has_length agrees, and must decide the end-to-end touch
// of a piece cut along a partner's neighbour.
#include <gtest/gtest.h>

#include <algorithm>
#include <optional>
#include <random>

#include "core/route/shared/chords.hpp"
#include "core/route/shared/trace.hpp"

namespace ember::test {
namespace {

using core::chord_constraints;
using core::chords_separated_by_edge;
using core::chords_surely_disjoint;

struct Outcome {
  int tested = 0, disjoint_said = 0, exact_disjoint = 0, wrong = 0;
};

std::vector<std::int8_t> sides(const Polygon& p, const Plane& plane) {
  std::vector<std::int8_t> s;
  for (const Point& v : p.vertices) s.push_back(static_cast<std::int8_t>(classify(v, plane)));
  return s;
}

/// Runs the filter on the pair if it is one the leaf would ask about (a
/// straddles b's plane, b touches a's) and compares with the exact answer.
void check_pair(const Polygon& a, const Polygon& b, Outcome& out) {
  const std::vector<std::int8_t> sa = sides(a, b.support), sb = sides(b, a.support);
  bool neg = false, pos = false, zero_b = false, neg_b = false, pos_b = false;
  for (const int s : sa) {
    neg |= s < 0;
    pos |= s > 0;
  }
  for (const int s : sb) {
    zero_b |= s == 0;
    neg_b |= s < 0;
    pos_b |= s > 0;
  }
  if (!(neg && pos) || !(zero_b || (neg_b && pos_b))) return;
  if (parallel(a.support, b.support)) return;
  std::vector<Plane> cons;
  chord_constraints(a, sa, cons);
  chord_constraints(b, sb, cons);
  const bool meet = core::line_region_nonempty(a.support, b.support, cons);
  const bool said = chords_surely_disjoint(a, a.support, sa, b, b.support, sb);
  ++out.tested;
  out.disjoint_said += said;
  out.exact_disjoint += !meet;
  out.wrong += said && meet;
}

std::optional<Polygon> triangle(const IntPoint& p, const IntPoint& q, const IntPoint& r) {
  return make_triangle(p, q, r);
}

TEST(Chords, NeverSaysDisjointWhenChordsMeetOnASmallLattice) {
  // Few points: shared vertices, vertices on edges and touching chords abound.
  std::mt19937 rng(7);
  std::uniform_int_distribution<std::int64_t> c(0, 4);
  const auto pt = [&] { return IntPoint{c(rng), c(rng), c(rng)}; };
  Outcome out;
  while (out.tested < 20000) {
    const IntPoint a0 = pt();
    const auto a = triangle(a0, pt(), pt());
    const auto b = triangle(out.tested % 3 == 0 ? a0 : pt(), pt(), pt());  // often a shared vertex
    if (a && b) check_pair(*a, *b, out);
  }
  EXPECT_EQ(out.wrong, 0);
  EXPECT_GT(out.disjoint_said, out.exact_disjoint / 3) << "the filter should decide most disjoint pairs";
  EXPECT_LT(out.exact_disjoint, out.tested) << "some pairs must meet";
}

TEST(Chords, TouchingThroughAnEdgeCrossingAtLargeCoordinates) {
  // b has a vertex w exactly on an edge of a (w = p + k (q - p) / 8), so a's
  // chord along b's plane ends at w, reached through the rounded crossing of
  // edge pq, and b's chord starts at w: they touch. Far from the origin the
  // rounding is largest; the filter must not call them disjoint.
  std::mt19937 rng(11);
  const std::int64_t m = kCoordLimit;
  std::uniform_int_distribution<std::int64_t> big(-m / 2, m / 2), off(-m / 4, m / 4), k(1, 7);
  Outcome out;
  int touching = 0;
  for (int n = 0; n < 20000; ++n) {
    const IntPoint p{big(rng) & ~7, big(rng) & ~7, big(rng) & ~7};
    const IntPoint d{(off(rng) / 8) * 8, (off(rng) / 8) * 8, (off(rng) / 8) * 8};
    const IntPoint q{p.x + d.x, p.y + d.y, p.z + d.z};
    const IntPoint r{big(rng), big(rng), big(rng)};
    const std::int64_t t = k(rng);
    const IntPoint w{p.x + t * d.x / 8, p.y + t * d.y / 8, p.z + t * d.z / 8};
    const auto a = triangle(p, q, r);
    const auto b =
        triangle(w, {w.x + off(rng), w.y + off(rng), w.z + off(rng)}, {w.x + off(rng), w.y + off(rng), w.z + off(rng)});
    if (!a || !b) continue;
    const int before = out.tested;
    check_pair(*a, *b, out);
    touching += out.tested > before;
  }
  EXPECT_EQ(out.wrong, 0);
  EXPECT_GT(touching, 1000);
}

TEST(Chords, RandomFullRangePairsAreDecidedSoundly) {
  std::mt19937 rng(3);
  const std::int64_t m = kCoordLimit;
  std::uniform_int_distribution<std::int64_t> big(-m, m), small(-(m >> 10), m >> 10);
  Outcome out;
  for (int n = 0; n < 40000; ++n) {
    const IntPoint o{big(rng), big(rng), big(rng)};
    const auto near = [&] {
      return IntPoint{std::clamp(o.x + small(rng), -m, m), std::clamp(o.y + small(rng), -m, m),
                      std::clamp(o.z + small(rng), -m, m)};
    };
    const auto a = triangle(near(), near(), near());
    const auto b = triangle(near(), near(), near());
    if (a && b) check_pair(*a, *b, out);
  }
  EXPECT_EQ(out.wrong, 0);
  EXPECT_GT(out.tested, 2000);
  EXPECT_GT(out.disjoint_said, out.exact_disjoint / 2);
}

/// The solid path's configuration: partners p and q of t share an edge that
/// crosses t; t's piece on the far side of q's plane from p touches p's chord
/// end to end. Checks the shortcut against the exact test on every piece of t
/// cut by q's plane, for both p and q; returns how many touching pairs it decided.
int check_shortcut(const Polygon& t, const Polygon& p, const Polygon& q, int& wrong) {
  int decided = 0;
  Polygon neg, pos;
  if (clip(t, q.support, neg, pos) != ClipSide::Both) return 0;
  for (const Polygon* piece : {&neg, &pos})
    for (const Polygon* other : {&p, &q}) {
      if (parallel(t.support, other->support)) continue;
      const std::vector<std::int8_t> sa = sides(*piece, other->support), sb = sides(*other, t.support);
      // What the leaf asks about: the piece straddles the other's plane, which meets t's.
      const auto has = [](const std::vector<std::int8_t>& s, int v) {
        return std::find(s.begin(), s.end(), v) != s.end();
      };
      if (!has(sa, -1) || !has(sa, 1) || !(has(sb, 0) || (has(sb, -1) && has(sb, 1)))) continue;
      std::vector<Plane> cons;
      chord_constraints(*piece, sa, cons);
      chord_constraints(*other, sb, cons);
      const bool length = core::line_region_has_length(t.support, other->support, cons);
      const bool said = chords_separated_by_edge(*piece, *other);
      wrong += said && length;
      decided += said;
    }
  return decided;
}

TEST(Chords, SeparatingEdgeShortcutAgreesWithTheExactTest) {
  // p = (e0, e1, a) and q = (e1, e0, b) share the edge e0 e1, which crosses
  // t's plane; coordinates near the grid's limit and on a small lattice
  // (degenerate contacts: shared points, edges in t's plane, coplanarity).
  for (const std::int64_t range : {std::int64_t{3}, kCoordLimit}) {
    std::mt19937 rng(static_cast<std::uint32_t>(range));
    std::uniform_int_distribution<std::int64_t> c(-range, range);
    const auto pt = [&] { return IntPoint{c(rng), c(rng), c(rng)}; };
    int wrong = 0, decided = 0, tried = 0;
    for (int n = 0; n < 20000; ++n) {
      const auto t = triangle(pt(), pt(), pt());
      const IntPoint e0 = pt(), e1 = pt();
      const auto p = triangle(e0, e1, pt());
      const auto q = triangle(e1, e0, pt());
      if (!t || !p || !q) continue;
      ++tried;
      decided += check_shortcut(*t, *p, *q, wrong);
    }
    EXPECT_EQ(wrong, 0) << "range " << range;
    EXPECT_GT(decided, tried / 20) << "range " << range << ": the shortcut should decide touching pieces";
  }
}

}  // namespace
}  // namespace ember::test
