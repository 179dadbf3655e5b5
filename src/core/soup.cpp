#include "core/soup.hpp"

#include <algorithm>
#include <cmath>

namespace ember::core {

void update_bounds(SoupPolygon& p) {
  constexpr double kMargin = 1.0 / 65536;
  std::array<double, 3> lo{HUGE_VAL, HUGE_VAL, HUGE_VAL}, hi{-HUGE_VAL, -HUGE_VAL, -HUGE_VAL};
  for (const Point& v : p.poly.vertices) {
    const auto a = approx(v);
    for (int i = 0; i < 3; ++i) {
      lo[i] = std::min(lo[i], a[i]);
      hi[i] = std::max(hi[i], a[i]);
    }
  }
  for (int i = 0; i < 3; ++i) {
    p.lo[i] = lo[i] - kMargin;
    p.hi[i] = hi[i] + kMargin;
  }
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
