// The compact forms of the core's polygons: a soup's flat approximations
// (SoupApprox) must answer the trace filter exactly as the polygons do, and a
// path piece (OutputPolygon::path) must expand to exactly the polygon the
// subdivision made.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <deque>
#include <memory>
#include <optional>
#include <random>

#include "core/model/soup.hpp"
#include "core/route/general/whole_triangles.hpp"
#include "geometry/clip.hpp"

namespace ember::core {
namespace {

IntPoint random_point(std::mt19937_64& rng, std::int64_t range) {
  std::uniform_int_distribution<std::int64_t> c(-range, range);
  return {c(rng), c(rng), c(rng)};
}

std::array<IntPoint, 3> random_triangle(std::mt19937_64& rng, std::int64_t range) {
  while (true) {
    const std::array<IntPoint, 3> t{random_point(rng, range), random_point(rng, range), random_point(rng, range)};
    const auto n = grid_normal(t[0], t[1], t[2]);
    if (n[0] != 0 || n[1] != 0 || n[2] != 0) return t;
  }
}

/// Splits p by a random axis plane through its box, as split_range does, and
/// keeps a random part (or p whole when the plane does not cut it). Appends
/// the step to `path`. False when the plane missed the box.
bool random_split(std::mt19937_64& rng, SoupPolygon& p, SplitPath& path) {
  const int axis = static_cast<int>(rng() % 3);
  const auto lo = static_cast<std::int64_t>(std::ceil(p.lo[axis])),
             hi = static_cast<std::int64_t>(std::floor(p.hi[axis]));
  if (hi < lo) return false;
  const std::int64_t at = lo + static_cast<std::int64_t>(rng() % static_cast<std::uint64_t>(hi - lo + 1));
  materialize(p);
  Polygon neg, pos;
  const ClipSide side = clip(*p.poly, axis_plane(axis, at), neg, pos);
  bool upper = side == ClipSide::Positive;
  if (side == ClipSide::Both) {
    upper = rng() % 2 == 0;
    *p.poly = upper ? pos : neg;
    ++p.splits;
    update_bounds(p);
  }
  path = std::make_shared<const SplitStep>(SplitStep{path, at, axis, upper});
  return true;
}

/// A soup of random triangles with corners in `corners` (sized by the
/// caller; they must outlive the soup), range(i) for triangle i: a third
/// stays unbuilt, a third is built uncut, a third is cut four times.
template <typename Range>
Soup mixed_soup(std::mt19937_64& rng, std::vector<std::array<IntPoint, 3>>& corners, Range&& range) {
  Soup soup;
  for (std::uint32_t i = 0; i < corners.size(); ++i) {
    corners[i] = random_triangle(rng, range(i));
    soup.push_back(unbuilt_triangle(corners[i], i, i % 2));
    SplitPath path;
    if (i % 3 == 1) materialize(soup.back());
    if (i % 3 == 2)
      for (int k = 0; k < 4; ++k) random_split(rng, soup.back(), path);
  }
  return soup;
}

TEST(Soup, FlatApproximationsFilterLinesLikeThePolygons) {
  std::mt19937_64 rng(11);
  std::vector<std::array<IntPoint, 3>> corners(400);
  const Soup soup = mixed_soup(rng, corners, [](std::uint32_t) { return std::int64_t{1000}; });
  SoupApprox flat;
  approximate(soup, flat);
  ASSERT_EQ(flat.begin.size(), soup.size() + 1);
  std::size_t misses = 0, checked = 0;
  std::uniform_int_distribution<std::int64_t> c(-1100 * 8, 1100 * 8);
  for (int l = 0; l < 300; ++l) {
    const AxisLine line{static_cast<int>(l % 3), DyadicNum(c(rng)), DyadicNum(c(rng)), 3};
    const std::array<double, 2> uv = line_point_approx(line);
    for (std::size_t i = 0; i < soup.size(); ++i) {
      const bool by_polygon = line_clearly_misses(line, uv, soup[i]);
      ASSERT_EQ(line_clearly_misses(line, uv, flat, i), by_polygon) << "polygon " << i << ", line " << l;
      misses += by_polygon;
      ++checked;
    }
  }
  // Both answers occur often, or the comparison proves little.
  EXPECT_GT(misses, checked / 4);
  EXPECT_LT(misses, checked);
}

/// gather's undecided vertices are tested from the flat approximation when
/// SoupApprox::grid marks them grid points: exactly the grid points, whose
/// approximations are their coordinates.
TEST(Soup, FlatApproximationsMarkExactlyTheGridPoints) {
  std::mt19937_64 rng(12);
  std::vector<std::array<IntPoint, 3>> corners(300);
  const Soup soup =
      mixed_soup(rng, corners, [](std::uint32_t i) { return i % 2 == 0 ? std::int64_t{1000} : kCoordLimit; });
  SoupApprox flat;
  approximate(soup, flat);
  ASSERT_EQ(flat.grid.size(), flat.verts.size());
  std::size_t grid = 0, other = 0;
  Polygon scratch;
  for (std::size_t i = 0; i < soup.size(); ++i) {
    const Polygon& poly = built_polygon(soup[i], scratch);
    const auto approx = flat.of(i);
    const auto marked = flat.grid_of(i);
    ASSERT_EQ(marked.size(), poly.vertices.size());
    for (std::size_t v = 0; v < marked.size(); ++v) {
      const std::optional<IntPoint> g = stored_grid_point(poly.vertices[v]);
      ASSERT_EQ(marked[v] != 0, g.has_value()) << "polygon " << i << " vertex " << v;
      if (!g) {
        ++other;
        continue;
      }
      ++grid;
      EXPECT_EQ(approx[v][0], static_cast<double>(g->x));
      EXPECT_EQ(approx[v][1], static_cast<double>(g->y));
      EXPECT_EQ(approx[v][2], static_cast<double>(g->z));
    }
  }
  EXPECT_GT(grid, 300u);   // corners, whole or kept by the cuts
  EXPECT_GT(other, 100u);  // and the cuts' new vertices
}

TEST(Soup, LeafPlaneFilterSignsAgreeWithTheExactTest) {
  // Triangles, whole and cut (homogeneous vertices), at small and at
  // full-range coordinates; every polygon's support plane against every
  // vertex of the soup, its own (on the plane: never decided by the filter)
  // and the others'.
  for (const std::int64_t range : {std::int64_t{1000}, kCoordLimit}) {
    std::mt19937_64 rng(static_cast<std::uint64_t>(range));
    Soup soup;
    std::vector<std::array<IntPoint, 3>> corners(120);
    for (std::uint32_t i = 0; i < corners.size(); ++i) {
      corners[i] = random_triangle(rng, range);
      soup.push_back(unbuilt_triangle(corners[i], i, 0));
      materialize(soup.back());
      SplitPath path;
      if (i % 2 == 1)
        for (int k = 0; k < 3; ++k) random_split(rng, soup.back(), path);
    }
    SoupApprox flat;
    approximate(soup, flat);
    std::size_t decided = 0, unsure = 0;
    for (const SoupPolygon& t : soup) {
      const Plane& plane = t.poly->support;
      const LeafPlaneFilter filter(PlaneApprox(plane), flat.max_abs);
      for (std::size_t i = 0; i < soup.size(); ++i) {
        const auto approx = flat.of(i);
        for (std::size_t v = 0; v < approx.size(); ++v) {
          const int s = filter.sign(approx[v]);
          const int exact = classify_exact(soup[i].poly->vertices[v], plane);
          if (&soup[i] == &t) {
            ASSERT_EQ(exact, 0);
          }
          if (s == LeafPlaneFilter::kUnsure) {
            ++unsure;
            continue;
          }
          ASSERT_EQ(s, exact) << "polygon " << i << " vertex " << v << ", range " << range;
          ++decided;
        }
      }
    }
    EXPECT_GT(decided, 10 * unsure);     // the filter decides nearly all ...
    EXPECT_GE(unsure, soup.size() * 3);  // ... but never a polygon's own vertices
  }
}

TEST(Soup, LeafPlaneFilterIsExactAtItsBound) {
  // Vertices at distances around the filter's bound from a plane: triangles
  // cut by the plane moved by 2^e bounds (e = -4 .. 4, either way), so that
  // their cut vertices lie exactly that far from it. Some are decided, some
  // are not; every decided sign is the exact one.
  // (At small coordinates the bound is below one unit of d: no vertex of
  // such a cut lies near it.)
  for (const std::int64_t range : {std::int64_t{1} << 20, kCoordLimit}) {
    std::mt19937_64 rng(static_cast<std::uint64_t>(range) + 7);
    std::size_t decided = 0, unsure = 0;
    for (int round = 0; round < 40; ++round) {
      const std::array<IntPoint, 3> t = random_triangle(rng, range);
      const Plane plane = *supporting_plane(t[0], t[1], t[2]);
      const PlaneApprox approx(plane);
      // The bound for vertices within `range` (the soup's max_abs is at most that).
      const double bound = LeafPlaneFilter(approx, static_cast<double>(range)).bound;
      Soup soup;
      std::vector<Plane> moved_by;
      std::deque<std::array<IntPoint, 3>> corners;  // unbuilt triangles point at their corners: stable addresses
      for (int e = -4; e <= 4; ++e)
        for (const int side : {-1, 1}) {
          // The moved plane is P + delta: its points x have P(x) = -delta.
          const auto delta = static_cast<__int128>(side * std::ldexp(bound, e));
          const __int128 shifted = plane.d.raw() + delta, limit = __int128{1} << 79;
          if (delta == 0 || shifted <= -limit || shifted >= limit) continue;  // beyond d's 79 bits
          const Plane moved{plane.a, plane.b, plane.c, OffsetCoef(shifted)};
          for (int tries = 0; tries < 20; ++tries) {
            corners.push_back(random_triangle(rng, range));
            SoupPolygon p = unbuilt_triangle(corners.back(), static_cast<std::uint32_t>(soup.size()), 0);
            materialize(p);
            Polygon neg, pos;
            if (clip(*p.poly, moved, neg, pos) != ClipSide::Both) continue;
            *p.poly = rng() % 2 ? pos : neg;
            ++p.splits;
            update_bounds(p);
            soup.push_back(std::move(p));
            moved_by.push_back(moved);
            break;
          }
        }
      SoupApprox flat;
      approximate(soup, flat);
      ASSERT_LE(flat.max_abs, static_cast<double>(range));
      const LeafPlaneFilter filter(approx, flat.max_abs);
      for (std::size_t i = 0; i < soup.size(); ++i) {
        const auto f = flat.of(i);
        for (std::size_t v = 0; v < f.size(); ++v) {
          const Point& x = soup[i].poly->vertices[v];
          if (classify_exact(x, moved_by[i]) != 0) continue;  // not a cut vertex
          const int exact = classify_exact(x, plane);
          ASSERT_NE(exact, 0);
          const int s = filter.sign(f[v]);
          if (s == LeafPlaneFilter::kUnsure) {
            ++unsure;
            continue;
          }
          ASSERT_EQ(s, exact) << "range " << range << ", round " << round << ", polygon " << i;
          ++decided;
        }
      }
    }
    EXPECT_GT(decided, 100u) << range;
    EXPECT_GT(unsure, 100u) << range;
  }
}

TEST(Soup, PathPiecesExpandToTheSubdivisionsPolygons) {
  std::mt19937_64 rng(5);
  std::vector<std::array<IntPoint, 3>> corners(300);
  std::vector<OutputPolygon> out;
  std::vector<SplitPath> paths;
  std::vector<Polygon> expected;
  std::size_t cuts = 0;
  for (std::uint32_t i = 0; i < corners.size(); ++i) {
    corners[i] = random_triangle(rng, 1 << 20);
    // Up to three pieces of one triangle that share the first splits (as
    // pieces in neighbouring boxes do), in a shuffled order.
    SoupPolygon prefix = unbuilt_triangle(corners[i], i, 0);
    SplitPath prefix_path;
    for (int k = 0; k < 6; ++k) random_split(rng, prefix, prefix_path);
    for (int branch = 0; branch < 3; ++branch) {
      SoupPolygon p = unbuilt_triangle(corners[i], i, 0);
      if (!unbuilt(prefix)) p.poly = std::make_unique<Polygon>(*prefix.poly);
      p.lo = prefix.lo;
      p.hi = prefix.hi;
      p.splits = prefix.splits;
      SplitPath path = prefix_path;
      for (int k = 0; k < 6; ++k) random_split(rng, p, path);
      if (p.splits == 0) continue;  // a path piece was cut at least once
      cuts += p.splits;
      OutputPolygon o;
      o.corners = &corners[i];
      o.id = i;
      o.splits = p.splits;
      o.whole_piece = true;
      o.path = static_cast<std::uint32_t>(paths.size());
      paths.push_back(path);
      out.push_back(std::move(o));
      expected.push_back(*p.poly);
    }
  }
  // Output order does not group a triangle's pieces.
  std::vector<std::size_t> perm(out.size());
  for (std::size_t k = 0; k < perm.size(); ++k) perm[k] = k;
  std::shuffle(perm.begin(), perm.end(), rng);
  std::vector<OutputPolygon> shuffled;
  std::vector<Polygon> shuffled_expected;
  for (const std::size_t k : perm) {
    shuffled.push_back(std::move(out[k]));
    shuffled_expected.push_back(expected[k]);
  }
  out = std::move(shuffled);
  expected = std::move(shuffled_expected);
  ASSERT_GT(out.size(), 100u);
  ASSERT_GT(cuts, 2 * out.size());
  expand_path_pieces(out, paths);
  for (std::size_t k = 0; k < out.size(); ++k) {
    EXPECT_EQ(out[k].path, OutputPolygon::kNoPath);
    ASSERT_EQ(out[k].vertices.size(), expected[k].vertices.size()) << "piece " << k;
    // The same points in the same order (same start): bit for bit.
    for (std::size_t v = 0; v < expected[k].vertices.size(); ++v) {
      const Point &a = out[k].vertices[v], &b = expected[k].vertices[v];
      EXPECT_TRUE(a.x == b.x && a.y == b.y && a.z == b.z && a.w == b.w) << "piece " << k << " vertex " << v;
    }
    EXPECT_TRUE(support_of(out[k]) == expected[k].support);
  }
}

}  // namespace
}  // namespace ember::core
