// The polygon-local BSP and classification targets (see pieces.hpp).
#include "core/route/shared/pieces.hpp"

#include <algorithm>
#include <cmath>

#include "core/route/shared/chords.hpp"
#include "numbers/divide.hpp"

namespace ember::core {

namespace {

/// True if no vertex of `poly` is strictly on the negative side of `plane`.
bool all_nonnegative(const Polygon& poly, const Plane& plane) {
  for (const Point& v : poly.vertices)
    if (classify(v, plane) < 0) return false;
  return true;
}

}  // namespace

/// Coplanar convex polygons overlap with positive area iff no edge of either
/// weakly separates them (separating-axis theorem in the common plane).
bool coplanar_overlap(const Polygon& a, const Polygon& b) {
  for (const Plane& e : b.edges)
    if (all_nonnegative(a, e)) return false;
  for (const Plane& e : a.edges)
    if (all_nonnegative(b, e)) return false;
  return true;
}

/// Case C4 for a coplanar polygon with a higher id: cut the piece along the
/// edges of `other`; parts outside become new pieces.
void cut_by_coplanar(std::vector<Piece>& pieces, std::size_t i, const Polygon& other, Polygon& neg, Polygon& pos) {
  for (const Plane& e : other.edges) {
    if (clip(pieces[i].poly, e, neg, pos) != ClipSide::Both) continue;
    pieces.push_back({std::move(pos)});
    std::swap(pieces[i].poly, neg);  // the old piece's buffers serve the next clip
  }
}

/// Case C3: split the piece by the other polygon's plane if their
/// intersection segment crosses the piece's interior with positive length.
/// `other_signs` are the other polygon's vertices classified against the
/// piece's plane.
bool split_by_transverse(const Polygon& poly, const Plane& support, const Polygon& other,
                         const std::vector<std::int8_t>& other_signs, std::vector<std::int8_t>& signs,
                         std::vector<Plane>& cons, Polygon& neg, Polygon& pos) {
  if (!classify_vertices(poly, other.support, signs).straddles() ||
      !chords_overlap(poly, support, signs, other, other_signs, cons))
    return false;
  return clip(poly, signs, other.support, neg, pos) == ClipSide::Both;
}

Sides sides_of(const std::vector<std::int8_t>& signs) {
  Sides s;
  for (const std::int8_t x : signs) {
    s.below |= x < 0;
    s.above |= x > 0;
    s.on += x == 0;
  }
  return s;
}

Sides classify_vertices(const Polygon& poly, const Plane& plane, std::vector<std::int8_t>& signs) {
  Sides sides;
  signs.resize(poly.vertices.size());
  const PlaneApprox approx(plane);  // converted once, not per vertex (four int128 -> double each)
  for (std::size_t v = 0; v < poly.vertices.size(); ++v) {
    const int s = classify(poly.vertices[v], plane, approx);
    signs[v] = static_cast<std::int8_t>(s);
    sides.below |= s < 0;
    sides.above |= s > 0;
    sides.on += s == 0;
  }
  return sides;
}

bool chords_overlap(const Polygon& poly, const Plane& support, const std::vector<std::int8_t>& signs,
                    const Polygon& other, const std::vector<std::int8_t>& other_signs, std::vector<Plane>& cons) {
  const ChordOverlap filtered = filter_chords(poly, support, signs, other, other.support, other_signs);
  if (filtered != ChordOverlap::kUnsure) return filtered == ChordOverlap::kYes;
  if (chords_separated_by_edge(poly, other)) return false;
  cons.clear();
  chord_constraints(poly, signs, cons);
  chord_constraints(other, other_signs, cons);
  return line_region_has_length(support, other.support, cons);
}

void cut_by_transverse(std::vector<Piece>& pieces, std::size_t i, const Plane& support, const Polygon& other,
                       const std::vector<std::int8_t>& other_signs, std::vector<std::int8_t>& signs,
                       std::vector<Plane>& cons, Polygon& neg, Polygon& pos) {
  if (!split_by_transverse(pieces[i].poly, support, other, other_signs, signs, cons, neg, pos)) return;
  std::swap(pieces[i].poly, neg);  // the old piece's buffers serve the next clip
  pieces.push_back({std::move(pos)});
}

namespace {

/// The signs of side(x) for the points into `signs`; false if all are
/// strictly positive or all strictly negative.
template <typename Points, typename Side>
bool signs_touch(const Points& points, Side&& side, std::vector<std::int8_t>& signs) {
  bool neg = false, pos = false, zero = false;
  signs.resize(points.size());
  for (std::size_t v = 0; v < points.size(); ++v) {
    const int s = side(points[v]);
    signs[v] = static_cast<std::int8_t>(s);
    zero |= s == 0;
    neg |= s < 0;
    pos |= s > 0;
  }
  return zero || (neg && pos);
}

}  // namespace

bool touches_plane(const Polygon& o, const Plane& plane, const PlaneApprox& approx, std::vector<std::int8_t>& signs) {
  return signs_touch(
      o.vertices, [&](const Point& x) { return classify(x, plane, approx); }, signs);
}

bool touches_plane(const std::array<IntPoint, 3>& corners, const Plane& plane, std::vector<std::int8_t>& signs) {
  return signs_touch(
      corners, [&](const IntPoint& x) { return classify(x, plane); }, signs);
}

bool meet_onto(const AxisSegment& seg, const Polygon& p, std::uint32_t operand, const Plane& S, const AxisPoint& x,
               Wnv& w, Wnv& delta) {
  if (coplanar(p.support, S)) {
    // Meets the segment only at x (the segment is transverse to S).
    const int loc = locate(p, x);
    if (loc == 0) return false;
    if (loc < 0) delta[operand] += same_orientation(p.support, S) ? 1 : -1;
    return true;
  }
  return add_crossing(seg, p, operand, w);
}

bool onto_segment(const Plane& S, const Dyadic& start, int k, const AxisPoint& x, AxisSegment& seg, int& side) {
  side = classify(to_point(start), S);
  if (side == 0) return false;
  const Plane pa = dyadic_axis_plane(start, k);
  const int dir = classify(x, pa);  // sign of x_k - start_k
  if (dir == 0) return false;
  const int i = (k + 1) % 3, j = (k + 2) % 3;
  const AxisLine line = axis_line(start, k);
  seg = AxisSegment{
      line, dyadic_axis_plane(start, i), dyadic_axis_plane(start, j), dir > 0 ? -pa : pa, side > 0 ? -S : S, dir, {},
      {},   line_point_approx(line)};
  const auto xa = approx(x);
  for (int a = 0; a < 3; ++a) {
    seg.lo[a] = std::min(approx_coord(start, a), xa[a]) - 1e-6;
    seg.hi[a] = std::max(approx_coord(start, a), xa[a]) + 1e-6;
  }
  return true;
}

namespace piece_targets {

/// Deterministic pseudo-random weights for alternative interior points.
std::uint64_t mix(std::uint64_t x) {
  x += 0x9e3779b97f4a7c15ULL;
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ULL;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebULL;
  return x ^ (x >> 31);
}

std::array<double, 2> interior_guess(const Polygon& f, int i, int j, int attempt, std::uint64_t seed) {
  // The centroid first, then random convex combinations.
  double ci = 0, cj = 0, total = 0;
  for (std::size_t v = 0; v < f.vertices.size(); ++v) {
    const double weight =
        attempt < 2 ? 1.0 : 0.05 + static_cast<double>(mix(seed * 131 + attempt * 17 + v) >> 11) * 0x1p-53;
    ci += weight * approx(f.vertices[v])[i];
    cj += weight * approx(f.vertices[v])[j];
    total += weight;
  }
  return {ci / total, cj / total};
}

void exact_centroid(const Polygon& f, std::size_t a, int i, int j, Dyadic& target) {
  const std::size_t n = f.vertices.size();
  const std::size_t tri[3] = {a, (a + 1) % n, (a + 2) % n};  // never collinear: the piece is strictly convex
  auto coord = [](const Point& p, int axis) -> const PointXYZ& { return axis == 0 ? p.x : (axis == 1 ? p.y : p.z); };
  const int sh = target.shift;
  for (const int axis : {i, j}) {
    // sum of floor(x_m * 2^(sh+2) / w_m) ~ 12 * centroid * 2^sh; |x/w| <= 2^26,
    // so each term is below 2^(26+54) and the sum below 2^82.
    __int128 sum = 0;
    for (const std::size_t m : tri) sum += floor_scaled_ratio(coord(f.vertices[m], axis), f.vertices[m].w, sh + 2);
    target.num[axis] = sum >= 0 ? (sum + 6) / 12 : -((-sum + 6) / 12);
  }
}

bool interior_point(const Polygon& f, const Dyadic& target, int k, AxisPoint& x) {
  return meet(axis_line(target, k), f.support, x) && locate(f, x) < 0;  // a piece of t has t's plane
}

}  // namespace piece_targets

}  // namespace ember::core
