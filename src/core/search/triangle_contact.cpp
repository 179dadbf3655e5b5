// Exact contact test of two grid triangles (step 1 of solid_proof.hpp).
// Coordinates satisfy |x| <= 2^25, so differences fit 26 bits (plus sign):
//   orient3d: 2x2 minors < 2^53, terms < 2^79, sum < 2^81  -> __int128;
//   orient2d: products < 2^52, difference < 2^53           -> int64;
//   chord directions |s| * |d|: < 2^81 * 2^26 * 2        -> __int128.
#include <cassert>
#include <cstdint>

#include "core/search/triangle_contact.hpp"

namespace ember::core {

namespace {

using i128 = __int128;
static_assert(kCoordLimit <= (std::int64_t{1} << 25), "the bit budget below assumes |x| <= 2^25");
constexpr int kDiffBits = 26;  // |x - y| <= 2^26 for grid coordinates
static_assert(2 * kDiffBits + 1 <= 62, "orient2d: two products < 2^52 each, difference < 2^53, fits int64");
static_assert(3 * kDiffBits + 1 + 2 <= 126, "orient3d: minors < 2^53, three terms < 2^79 each, sum < 2^81");
static_assert((3 * kDiffBits + 3) + kDiffBits + 1 <= 126, "chord |s| d: s < 2^81, d < 2^26, two terms < 2^108");

int sign(i128 v) { return v > 0 ? 1 : (v < 0 ? -1 : 0); }

/// det[b-a; c-a; d-a] (plane.hpp's grid_orient3d).
i128 orient3d(const IntPoint& a, const IntPoint& b, const IntPoint& c, const IntPoint& d) {
  return grid_orient3d(a, b, c, d);
}

/// orient3d(t[0], t[1], t[2], p) = n . (p - t[0]) with the stored normal n:
/// the same value (n has components < 2^53, differences < 2^27, so each
/// product < 2^80 and the sum < 2^82) for three multiplications instead of nine.
i128 side(const ContactTriangle& t, const IntPoint& p) { return grid_side(t.p()[0], t.n, p); }

/// Three corners' sides of a plane all strictly positive or all strictly
/// negative: the triangle lies beside the plane and cannot meet it.
bool strictly_one_side(const i128 (&s)[3]) {
  return (s[0] > 0 && s[1] > 0 && s[2] > 0) || (s[0] < 0 && s[1] < 0 && s[2] < 0);
}

/// The sides (grid_side) of b's corners against the plane of a (normal na).
/// Always inlined: returned through memory, the 48 bytes would be stored and
/// reloaded on every pair the partner search tests.
struct Sides {
  i128 s[3];
};
[[gnu::always_inline]] inline Sides sides(const std::array<IntPoint, 3>& a, const std::array<std::int64_t, 3>& na,
                                          const std::array<IntPoint, 3>& b) {
  return {{grid_side(a[0], na, b[0]), grid_side(a[0], na, b[1]), grid_side(a[0], na, b[2])}};
}

/// A 2D view of a plane: coordinates (u, v) after dropping axis `drop`.
struct Projection {
  int u, v;
  explicit Projection(int drop) : u((drop + 1) % 3), v((drop + 2) % 3) {}
  static std::int64_t get(const IntPoint& p, int axis) { return axis == 0 ? p.x : (axis == 1 ? p.y : p.z); }
  std::int64_t orient(const IntPoint& p, const IntPoint& q, const IntPoint& r) const {
    return (get(q, u) - get(p, u)) * (get(r, v) - get(p, v)) - (get(q, v) - get(p, v)) * (get(r, u) - get(p, u));
  }
};

/// The axis along which a plane with normal n projects without collapsing.
int dominant_axis(const std::array<std::int64_t, 3>& n) {
  const std::int64_t a[3] = {n[0] < 0 ? -n[0] : n[0], n[1] < 0 ? -n[1] : n[1], n[2] < 0 ? -n[2] : n[2]};
  if (a[0] >= a[1] && a[0] >= a[2]) return 0;
  return a[1] >= a[2] ? 1 : 2;
}

/// Closed coplanar triangles meet unless an edge line of one has the other
/// strictly on its outer side (separating axis theorem for convex polygons).
[[gnu::noinline]] bool coplanar_meet(const std::array<IntPoint, 3>& a, const std::array<IntPoint, 3>& b,
                                     const Projection& pr) {
  const auto separated_by_edge_of = [&](const std::array<IntPoint, 3>& s, const std::array<IntPoint, 3>& o) {
    const int orientation = sign(pr.orient(s[0], s[1], s[2]));
    for (int i = 0; i < 3; ++i) {
      bool all_out = true;
      for (const IntPoint& p : o) all_out &= orientation * sign(pr.orient(s[i], s[(i + 1) % 3], p)) < 0;
      if (all_out) return true;
    }
    return false;
  };
  return !separated_by_edge_of(a, b) && !separated_by_edge_of(b, a);
}

/// The canonical order of a triangle for the straddle test below, from the
/// signs s of its vertices against the other triangle's plane (not all equal
/// and non-zero, not all zero): its vertices as (alone, x, y) where `alone`
/// is on one closed side and x, y on the other, and `flip` set when that
/// other plane must be turned around so that `alone` is on its positive
/// closed side and x, y on its negative one. A vertex may sit on the plane
/// only if it is alone (then x and y are strictly on one side) or if it is
/// x or y.
struct Straddle {
  int alone = 0;
  bool flip = false;
};
Straddle straddle(const int (&s)[3]) {
  for (int k = 0; k < 3; ++k) {
    const int t = s[k], u = s[(k + 1) % 3], v = s[(k + 2) % 3];
    if ((t > 0 && u <= 0 && v <= 0) || (t == 0 && u < 0 && v < 0)) return {k, false};
    if ((t < 0 && u >= 0 && v >= 0) || (t == 0 && u > 0 && v > 0)) return {k, true};
  }
  return {0, false};  // unreachable for the sign patterns the caller passes
}

/// Closed non-coplanar triangles a and b, each meeting the other's plane
/// (sa: a's vertices against b's plane, sb: b's against a's), intersect iff
/// the segments in which they cross the planes' common line overlap
/// (Guigue and Devillers 2003). With a = (p1, q1, r1) and b = (p2, q2, r2) in
/// canonical order (p1 alone on the positive side of b's plane, turned if
/// needed by swapping q2 and r2; p2 likewise for a's plane), the segments
/// overlap iff neither ends before the other begins, which two orientations
/// of one vertex of each against an edge of the other decide.
/// Not inlined, nor coplanar_meet: apart_triangles_meet's callers mostly end
/// at its plane tests, which stay lean without them (inlined, they would
/// bloat the broad phases' inner loops for the few pairs that reach them).
[[gnu::noinline]] bool straddling_triangles_meet(const std::array<IntPoint, 3>& a, const std::array<IntPoint, 3>& b,
                                                 const int (&sa)[3], const int (&sb)[3]) {
  const Straddle ca = straddle(sa), cb = straddle(sb);
  // ca.flip turns b's plane (swap b's last two), cb.flip turns a's.
  const IntPoint& p1 = a[ca.alone];
  const IntPoint& q1 = a[(ca.alone + (cb.flip ? 2 : 1)) % 3];
  const IntPoint& r1 = a[(ca.alone + (cb.flip ? 1 : 2)) % 3];
  const IntPoint& p2 = b[cb.alone];
  const IntPoint& q2 = b[(cb.alone + (ca.flip ? 2 : 1)) % 3];
  const IntPoint& r2 = b[(cb.alone + (ca.flip ? 1 : 2)) % 3];
  return orient3d(q1, q2, p2, p1) <= 0 && orient3d(p1, r2, p2, r1) <= 0;
}

/// Direction of the segment (starting at shared vertex v) in which triangle
/// (v, a1, a2) meets a plane through v, from the signed sides s1, s2 of a1,
/// a2; false if the triangle meets the plane only at v.
bool chord_direction(const IntPoint& v, const IntPoint& a1, const IntPoint& a2, i128 s1, i128 s2,
                     std::array<i128, 3>& dir) {
  const std::array<i128, 3> d1{a1.x - v.x, a1.y - v.y, a1.z - v.z}, d2{a2.x - v.x, a2.y - v.y, a2.z - v.z};
  if (s1 == 0) {
    dir = d1;
    return true;
  }
  if (s2 == 0) {
    dir = d2;
    return true;
  }
  if ((s1 > 0) == (s2 > 0)) return false;
  const i128 w1 = s2 < 0 ? -s2 : s2, w2 = s1 < 0 ? -s1 : s1;  // |s2| d1 + |s1| d2 lies in the plane
  for (int k = 0; k < 3; ++k) dir[k] = w1 * d1[k] + w2 * d2[k];
  return true;
}

/// Coplanar triangles (v, a1, a2) and (v, b1, b2) meet beyond v iff a ray of
/// one wedge at v lies in the other's closed wedge.
bool wedges_meet(const IntPoint& v, const IntPoint& a1, const IntPoint& a2, const IntPoint& b1, const IntPoint& b2,
                 const Projection& pr) {
  const auto in_wedge = [&](const IntPoint& e1, const IntPoint& e2, const IntPoint& r) {
    const bool ccw = pr.orient(v, e1, e2) > 0;
    const IntPoint& lo = ccw ? e1 : e2;
    const IntPoint& hi = ccw ? e2 : e1;
    return pr.orient(v, lo, r) >= 0 && pr.orient(v, r, hi) >= 0;
  };
  return in_wedge(a1, a2, b1) || in_wedge(a1, a2, b2) || in_wedge(b1, b2, a1) || in_wedge(b1, b2, a2);
}

}  // namespace

ContactTriangle contact_triangle(const std::array<IntPoint, 3>& p, const std::array<std::uint32_t, 3>& ids) {
  return {&p, grid_normal(p[0], p[1], p[2]), ids, 0};
}

bool triangles_meet_improperly(const std::array<IntPoint, 3>& a, const std::array<IntPoint, 3>& b) {
  // Ids equal iff positions equal: a's corners 0..2, b's corner j the id of an
  // equal corner of a, else 3 + j.
  std::array<std::uint32_t, 3> ib{3, 4, 5};
  for (int j = 0; j < 3; ++j)
    for (int i = 0; i < 3; ++i)
      if (b[j] == a[i]) ib[j] = static_cast<std::uint32_t>(i);
  return triangles_meet_improperly(contact_triangle(a, {0, 1, 2}), contact_triangle(b, ib));
}

bool triangles_meet(const std::array<IntPoint, 3>& a, const std::array<IntPoint, 3>& b) {
  // With no corner counted as shared, every common point is improper: the
  // closed-set tests decide (equal positions included).
  return apart_triangles_meet(a, grid_normal(a[0], a[1], a[2]), b, grid_normal(b[0], b[1], b[2]));
}

bool beside_plane(const std::array<IntPoint, 3>& a, const std::array<std::int64_t, 3>& na,
                  const std::array<IntPoint, 3>& b) {
  return strictly_one_side(sides(a, na, b).s);
}

bool triangles_meet_improperly(const ContactTriangle& ta, const ContactTriangle& tb) {
  const std::array<IntPoint, 3>&a = ta.p(), &b = tb.p();
  int shared = 0, ia = -1, ib = -1;  // a[ia] == b[ib] when exactly one vertex is shared
  bool a_shared[3] = {false, false, false}, b_shared[3] = {false, false, false};
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      if (ta.id[i] == tb.id[j]) {
        ++shared;
        a_shared[i] = b_shared[j] = true;
        ia = i;
        ib = j;
      }
  if (shared >= 3) return true;  // the same triangle twice (either orientation)
  // Two triangles of a certified star meet only in its vertex and their
  // common edge (vertex_stars.hpp).
  for (int i = 0; i < 3; ++i)
    if (a_shared[i] && (ta.embedded >> i & 1)) return false;
  const auto side_of_b = [&](const IntPoint& p) { return side(tb, p); };
  const auto side_of_a = [&](const IntPoint& p) { return side(ta, p); };
  if (shared == 2) {
    int i = 0, j = 0;
    while (a_shared[i]) ++i;
    while (b_shared[j]) ++j;
    if (side_of_a(b[j]) != 0) return false;        // not coplanar: they meet exactly along the shared edge
    const int e0 = (i + 1) % 3, e1 = (i + 2) % 3;  // the shared edge, as in a
    const Projection pr(dominant_axis(ta.n));
    return sign(pr.orient(a[e0], a[e1], a[i])) == sign(pr.orient(a[e0], a[e1], b[j]));
  }
  if (shared == 1) {
    const IntPoint& v = a[ia];
    const IntPoint &a1 = a[(ia + 1) % 3], &a2 = a[(ia + 2) % 3];
    const IntPoint &b1 = b[(ib + 1) % 3], &b2 = b[(ib + 2) % 3];
    const i128 s1 = side_of_b(a1), s2 = side_of_b(a2);
    if ((s1 > 0 && s2 > 0) || (s1 < 0 && s2 < 0)) return false;  // a meets b's plane only at v
    if (s1 == 0 && s2 == 0) return wedges_meet(v, a1, a2, b1, b2, Projection(dominant_axis(ta.n)));  // coplanar
    // Both meet the other's plane in segments from v along the planes' common line.
    std::array<i128, 3> da{}, db{};
    chord_direction(v, a1, a2, s1, s2, da);
    if (!chord_direction(v, b1, b2, side_of_a(b1), side_of_a(b2), db)) return false;
    for (int k = 0; k < 3; ++k)
      if (da[k] != 0) return (da[k] > 0) == (db[k] > 0);  // parallel: one component decides
    return true;  // unreachable for non-degenerate triangles; answer "meet" to stay safe
  }
  // No shared vertex.
  return apart_triangles_meet(a, ta.n, b, tb.n);
}

namespace {

/// The rest of apart_triangles_meet once b's corners are known to meet a's
/// plane (sb: their signs against it, not all equal and non-zero).
bool meet_from_signs(const std::array<IntPoint, 3>& a, const std::array<std::int64_t, 3>& na,
                     const std::array<IntPoint, 3>& b, const std::array<std::int64_t, 3>& nb, const CornerSigns& sb) {
  const Sides a_side = sides(b, nb, a);
  const i128(&sa)[3] = a_side.s;
  if (strictly_one_side(sa)) return false;
  // a in b's plane: then b is in a's too (sb all zero), coplanar triangles.
  if (sa[0] == 0 && sa[1] == 0 && sa[2] == 0) return coplanar_meet(a, b, Projection(dominant_axis(na)));
  const int signs_a[3] = {sign(sa[0]), sign(sa[1]), sign(sa[2])};
  return straddling_triangles_meet(a, b, signs_a, sb.s);
}

}  // namespace

bool apart_triangles_meet(const std::array<IntPoint, 3>& a, const std::array<std::int64_t, 3>& na,
                          const std::array<IntPoint, 3>& b, const std::array<std::int64_t, 3>& nb) {
  // b against a's plane first (beside_plane).
  const Sides b_side = sides(a, na, b);
  const i128(&sb)[3] = b_side.s;
  if (strictly_one_side(sb)) return false;
  return meet_from_signs(a, na, b, nb, CornerSigns{{sign(sb[0]), sign(sb[1]), sign(sb[2])}});
}

bool apart_triangles_meet(const std::array<IntPoint, 3>& a, const std::array<std::int64_t, 3>& na,
                          const std::array<IntPoint, 3>& b, const std::array<std::int64_t, 3>& nb,
                          const CornerSigns& sb) {
  assert(!sb.strictly_one_side());
  return meet_from_signs(a, na, b, nb, sb);
}

int PlaneSideFilter::exact_sign(const IntPoint& p) const { return sign(grid_side(origin_, normal_, p)); }

}  // namespace ember::core
