#include "core/model/soup.hpp"

#include <algorithm>
#include <cmath>

namespace ember::core {

namespace {
constexpr double kBoundsMargin = 1.0 / 65536;
}  // namespace

void approx_bounds(const Polygon& poly, std::array<double, 3>& lo, std::array<double, 3>& hi) {
  lo = {HUGE_VAL, HUGE_VAL, HUGE_VAL};
  hi = {-HUGE_VAL, -HUGE_VAL, -HUGE_VAL};
  for (const Point& v : poly.vertices)
    for (int i = 0; i < 3; ++i) {
      lo[i] = std::min(lo[i], approx(v)[i]);
      hi[i] = std::max(hi[i], approx(v)[i]);
    }
  for (int i = 0; i < 3; ++i) {
    lo[i] -= kBoundsMargin;
    hi[i] += kBoundsMargin;
  }
}

void update_bounds(SoupPolygon& p) {
  if (!unbuilt(p)) {
    approx_bounds(*p.poly, p.lo, p.hi);
    return;
  }
  // The approximation of a grid point (w = 1) is its exact coordinates:
  // the integer extremes, converted once (exactly: |x| <= 2^25), are the
  // same bounds as the extremes of the converted corners, for a third of
  // the conversions (every input triangle passes here).
  const std::array<IntPoint, 3>& c = *p.corners;
  const auto axis = [&](std::int64_t IntPoint::*x, int i) {
    const std::int64_t a = c[0].*x, b = c[1].*x, d = c[2].*x;
    p.lo[i] = static_cast<double>(std::min({a, b, d})) - kBoundsMargin;
    p.hi[i] = static_cast<double>(std::max({a, b, d})) + kBoundsMargin;
  };
  axis(&IntPoint::x, 0);
  axis(&IntPoint::y, 1);
  axis(&IntPoint::z, 2);
}

SoupPolygon unbuilt_triangle(const std::array<IntPoint, 3>& c, std::uint32_t id, std::uint32_t operand) {
  SoupPolygon p;
  p.corners = &c;
  p.id = id;
  p.operand = operand;
  update_bounds(p);
  return p;
}

void materialize(SoupPolygon& p) {
  if (!unbuilt(p)) return;
  const std::array<IntPoint, 3>& c = *p.corners;
  p.poly = std::make_unique<Polygon>();
  assign_triangle(c[0], c[1], c[2], *p.poly);  // a soup triangle has area
}

bool line_clearly_misses(const AxisLine& l, const std::array<double, 2>& uv, const SoupPolygon& p) {
  if (!unbuilt(p)) return line_clearly_misses(l, uv, *p.poly);
  const std::array<IntPoint, 3>& c = *p.corners;
  // The support's normal is the grid normal (p1 - p0) x (p2 - p0), exact in int64.
  const std::int64_t n = grid_normal(c[0], c[1], c[2])[static_cast<std::size_t>(l.axis)];
  std::array<std::array<double, 3>, 3> v;
  for (int i = 0; i < 3; ++i)
    v[i] = {static_cast<double>(c[i].x), static_cast<double>(c[i].y), static_cast<double>(c[i].z)};
  return line_clearly_misses(l, uv, (n > 0) - (n < 0), 3,
                             [&](std::size_t i) -> const std::array<double, 3>& { return v[i]; });
}

void approximate(const Soup& soup, SoupApprox& out) {
  out.verts.clear();
  out.grid.clear();
  out.begin.assign(1, 0);
  out.normal_sign.clear();
  for (const SoupPolygon& p : soup) {
    std::array<std::int8_t, 3> sign;
    if (unbuilt(p)) {
      // Grid points are exact in double; the grid normal is the support's.
      for (const IntPoint& c : *p.corners) {
        out.verts.push_back({static_cast<double>(c.x), static_cast<double>(c.y), static_cast<double>(c.z)});
        out.grid.push_back(1);
      }
      const std::array<std::int64_t, 3> n = grid_normal((*p.corners)[0], (*p.corners)[1], (*p.corners)[2]);
      for (int a = 0; a < 3; ++a) sign[a] = static_cast<std::int8_t>((n[a] > 0) - (n[a] < 0));
    } else {
      for (const Point& v : p.poly->vertices) {
        out.verts.push_back(approx(v));
        // A stored grid point's approximation is its exact coordinates.
        out.grid.push_back(stored_grid_point(v).has_value() ? 1 : 0);
      }
      for (int a = 0; a < 3; ++a) sign[a] = static_cast<std::int8_t>(p.poly->support.normal(a).sign());
    }
    out.normal_sign.push_back(sign);
    out.begin.push_back(static_cast<std::uint32_t>(out.verts.size()));
  }
  out.max_abs = 0;
  for (const std::array<double, 3>& v : out.verts)
    out.max_abs = std::max({out.max_abs, std::fabs(v[0]), std::fabs(v[1]), std::fabs(v[2])});
}

bool line_clearly_misses(const AxisLine& l, const std::array<double, 2>& uv, const SoupApprox& a, std::size_t i) {
  const std::span<const std::array<double, 3>> v = a.of(i);
  return line_clearly_misses(l, uv, a.normal_sign[i][static_cast<std::size_t>(l.axis)], v.size(),
                             [&](std::size_t k) -> const std::array<double, 3>& { return v[k]; });
}

Plane support_of(const SoupPolygon& p) {
  if (!unbuilt(p)) return p.poly->support;
  const std::array<IntPoint, 3>& c = *p.corners;
  return *supporting_plane(c[0], c[1], c[2]);  // a soup triangle has area
}

const Polygon& built_polygon(const SoupPolygon& p, Polygon& scratch) {
  if (!unbuilt(p)) return *p.poly;
  const std::array<IntPoint, 3>& c = *p.corners;
  assign_triangle(c[0], c[1], c[2], scratch);  // has area: it is a soup triangle
  return scratch;
}

Dyadic with_shift(const Dyadic& p, int s) {
  Dyadic r = p;
  for (auto& n : r.num) n *= static_cast<__int128>(1) << (s - p.shift);
  r.shift = s;
  return r;
}

int compare(const Dyadic& p, int axis, std::int64_t value) {
  const __int128 a = p.num[axis], b = static_cast<__int128>(value) * (static_cast<__int128>(1) << p.shift);
  return a < b ? -1 : (a > b ? 1 : 0);
}

Plane dyadic_axis_plane(const Dyadic& p, int axis) {
  const std::int64_t scale = std::int64_t{1} << p.shift;  // <= 2^52: a NormalCoef
  Plane pl{0, 0, 0, -p.num[axis]};
  (axis == 0 ? pl.a : axis == 1 ? pl.b : pl.c) = scale;
  return pl;
}

Point to_point(const Dyadic& p) {
  Point pt{PointXYZ(p.num[0]), PointXYZ(p.num[1]), PointXYZ(p.num[2]), PointW(std::int64_t{1} << p.shift), {}};
  detail::cache_approx(pt);
  return pt;
}

AxisLine axis_line(const Dyadic& p, int axis) {
  return AxisLine{axis, DyadicNum(p.num[(axis + 1) % 3]), DyadicNum(p.num[(axis + 2) % 3]), p.shift};
}

double approx_coord(const Dyadic& p, int axis) {
  return to_double(p.num[axis]) / static_cast<double>(std::int64_t{1} << p.shift);  // exact power of two
}

}  // namespace ember::core
