// Ear clipping on the grid (see face_triangulation.hpp).
#include "core/input/face_triangulation.hpp"

#include <cstdlib>
#include <type_traits>

namespace ember::core {

namespace {

using i128 = __int128;

struct P2 {
  std::int64_t u, v;
};

/// Twice the signed area of (a, b, c): coordinates <= 2^26 apart, so the
/// products stay below 2^54 (exact in int128 with room to spare).
static_assert(std::is_same_v<decltype(CoordDiff{} * CoordDiff{} - CoordDiff{} * CoordDiff{}), Int<55>> &&
                  Int<55>::bits < 127,
              "grid orientation: 27 + 27 = 54 bits per product, difference -> 55, fits int128");
i128 orient(const P2& a, const P2& b, const P2& c) {
  return i128(b.u - a.u) * (c.v - a.v) - i128(b.v - a.v) * (c.u - a.u);
}

/// Newell normal, exact: each term is below 2^27 * 2^27 = 2^54, so any face
/// with fewer than 2^70 corners fits in int128.
static_assert(std::is_same_v<decltype(CoordDiff{} * CoordDiff{}), Int<54>> && 54 + 70 < 127,
              "Newell term: 27 + 27 = 54 bits; 2^70 terms still fit int128");
std::array<i128, 3> newell(std::span<const IntPoint> c) {
  std::array<i128, 3> n{0, 0, 0};
  for (std::size_t i = 0; i < c.size(); ++i) {
    const IntPoint& a = c[i];
    const IntPoint& b = c[(i + 1) % c.size()];
    n[0] += i128(a.y - b.y) * (a.z + b.z);
    n[1] += i128(a.z - b.z) * (a.x + b.x);
    n[2] += i128(a.x - b.x) * (a.y + b.y);
  }
  return n;
}

/// Projects away the dominant axis, keeping the polygon's orientation: the
/// projected polygon runs counter-clockwise when the normal points along +axis.
std::vector<P2> project(std::span<const IntPoint> c, const std::array<i128, 3>& n) {
  int axis = 0;
  for (int a = 1; a < 3; ++a)
    if ((n[a] < 0 ? -n[a] : n[a]) > (n[axis] < 0 ? -n[axis] : n[axis])) axis = a;
  const bool flip = n[axis] < 0;
  std::vector<P2> p;
  p.reserve(c.size());
  for (const IntPoint& q : c) {
    const std::int64_t xyz[3] = {q.x, q.y, q.z};
    std::int64_t u = xyz[(axis + 1) % 3], v = xyz[(axis + 2) % 3];
    if (flip) std::swap(u, v);
    p.push_back({u, v});
  }
  return p;
}

/// Closed point-in-triangle for a counter-clockwise triangle.
bool inside_closed(const P2& a, const P2& b, const P2& c, const P2& q) {
  return orient(a, b, q) >= 0 && orient(b, c, q) >= 0 && orient(c, a, q) >= 0;
}

bool same(const P2& a, const P2& b) { return a.u == b.u && a.v == b.v; }

/// Is (prev, cur, next) an ear of the remaining polygon: strictly convex and
/// no other remaining corner in it (corners at the same position as one of
/// the ear's corners do not block it, so touching holes still clip).
bool is_ear(const std::vector<P2>& p, const std::vector<std::uint32_t>& ring, std::size_t i) {
  const std::size_t n = ring.size();
  const P2& a = p[ring[(i + n - 1) % n]];
  const P2& b = p[ring[i]];
  const P2& c = p[ring[(i + 1) % n]];
  if (orient(a, b, c) <= 0) return false;
  for (std::size_t k = 0; k < n; ++k) {
    if (k == i || k == (i + 1) % n || k == (i + n - 1) % n) continue;
    const P2& q = p[ring[k]];
    if (same(q, a) || same(q, b) || same(q, c)) continue;
    if (inside_closed(a, b, c, q)) return false;
  }
  return true;
}

void fan(std::size_t n, std::vector<std::array<std::uint32_t, 3>>& out) {
  for (std::uint32_t i = 1; i + 1 < n; ++i) out.push_back({0, i, i + 1});
}

bool is_convex(const std::vector<P2>& p) {
  const std::size_t n = p.size();
  for (std::size_t i = 0; i < n; ++i)
    if (orient(p[i], p[(i + 1) % n], p[(i + 2) % n]) < 0) return false;
  return true;
}

}  // namespace

void triangulate_polygon(std::span<const IntPoint> corners, std::vector<std::array<std::uint32_t, 3>>& out) {
  const std::size_t n = corners.size();
  if (n <= 3) {
    fan(n, out);
    return;
  }
  const std::array<i128, 3> normal = newell(corners);
  if (normal[0] == 0 && normal[1] == 0 && normal[2] == 0) {  // no area on the grid: nothing to choose
    fan(n, out);
    return;
  }
  const std::vector<P2> p = project(corners, normal);
  // Convex faces (the common case) keep the fan; ear clipping is quadratic
  // per ear, so huge concave faces keep it too (their proof may then fail).
  constexpr std::size_t kMaxEarClipCorners = 1024;
  if (n > kMaxEarClipCorners || is_convex(p)) {
    fan(n, out);
    return;
  }
  std::vector<std::uint32_t> ring(n);
  for (std::uint32_t i = 0; i < n; ++i) ring[i] = i;
  std::vector<std::array<std::uint32_t, 3>> ears;
  ears.reserve(n - 2);
  while (ring.size() > 3) {
    std::size_t i = 0;
    while (i < ring.size() && !is_ear(p, ring, i)) ++i;
    if (i == ring.size()) {  // not simple in projection (self-overlapping, twisted): keep the fan
      fan(n, out);
      return;
    }
    const std::size_t m = ring.size();
    ears.push_back({ring[(i + m - 1) % m], ring[i], ring[(i + 1) % m]});
    ring.erase(ring.begin() + static_cast<std::ptrdiff_t>(i));
  }
  ears.push_back({ring[0], ring[1], ring[2]});
  out.insert(out.end(), ears.begin(), ears.end());
}

}  // namespace ember::core
