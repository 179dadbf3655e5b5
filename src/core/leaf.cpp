// Leaf computation (paper Sections 4.3 and 4.4): every polygon is cut by all
// others with a polygon-local BSP, then each enabled piece is classified by
// tracing a path from the leaf's reference point to an interior point.
#include <algorithm>
#include <cmath>
#include <cstdint>

#include "core/solve.hpp"
#include "core/trace.hpp"
#include "ember/numbers/divide.hpp"
#include "ember/error.hpp"

namespace ember::core {

namespace {

struct Piece {
  Polygon poly;
  bool disabled = false;  ///< overlapped by a coplanar polygon with a lower id (Fig. 8)
};

bool boxes_overlap(const SoupPolygon& a, const SoupPolygon& b) { return !box_disjoint(a, b.lo, b.hi); }

/// True if no vertex of `poly` is strictly on the negative side of `plane`.
bool all_nonnegative(const Polygon& poly, const Plane& plane) {
  for (const Point& v : poly.vertices)
    if (classify(v, plane) < 0) return false;
  return true;
}

/// Coplanar convex polygons overlap with positive area iff no edge of either
/// weakly separates them (separating-axis theorem in the common plane).
bool coplanar_overlap(const Polygon& a, const Polygon& b) {
  for (const Plane& e : b.edges)
    if (all_nonnegative(a, e)) return false;
  for (const Plane& e : a.edges)
    if (all_nonnegative(b, e)) return false;
  return true;
}

/// Case C4: cut the piece along the edges of the coplanar polygon `other`;
/// parts outside become new pieces, the part inside stays in pieces[i].
void cut_by_coplanar(std::vector<Piece>& pieces, std::size_t i, const Polygon& other, bool disable) {
  Polygon neg, pos;
  for (const Plane& e : other.edges) {
    const ClipSide side = clip(pieces[i].poly, e, neg, pos);
    if (side == ClipSide::Both) {
      pieces.push_back({pos, pieces[i].disabled});
      pieces[i].poly = neg;
    }
  }
  if (disable) pieces[i].disabled = true;
}

/// Appends the edges of a convex polygon that can bound the chord where a
/// line in the plane `cut` crosses it: edges whose end points lie on opposite
/// sides of `cut` or touch it. The other edges contain the whole chord.
void chord_constraints(const Polygon& poly, const std::vector<std::int8_t>& signs, std::vector<Plane>& out) {
  const std::size_t n = poly.edges.size();
  for (std::size_t i = 0; i < n; ++i) {
    const int a = signs[i], b = signs[(i + 1) % n];  // edge i runs from vertex i to i+1
    if (a == 0 || b == 0 || a != b) out.push_back(poly.edges[i]);
  }
}

/// Double approximation of the interval that a convex polygon's chord along
/// `plane` covers on the direction `dir`, from the cached vertex
/// approximations and the vertices' exact signs against the plane.
std::array<double, 2> approx_chord(const Polygon& poly, const std::vector<std::int8_t>& signs, const Plane& plane,
                                   const std::array<double, 3>& dir) {
  const double na = static_cast<double>(plane.a.raw()), nb = static_cast<double>(plane.b.raw()),
               nc = static_cast<double>(plane.c.raw()), nd = plane.d.to_double();
  std::array<double, 2> range{HUGE_VAL, -HUGE_VAL};
  const auto add = [&](const std::array<double, 3>& x) {
    const double t = dir[0] * x[0] + dir[1] * x[1] + dir[2] * x[2];
    range[0] = std::min(range[0], t);
    range[1] = std::max(range[1], t);
  };
  const std::size_t n = poly.vertices.size();
  for (std::size_t i = 0; i < n; ++i) {
    const std::size_t j = i + 1 == n ? 0 : i + 1;
    const auto& fi = poly.vertices[i].f;
    if (signs[i] == 0) add(fi);
    if (signs[i] * signs[j] >= 0) continue;
    const auto& fj = poly.vertices[j].f;
    const double di = na * fi[0] + nb * fi[1] + nc * fi[2] + nd;
    const double dj = na * fj[0] + nb * fj[1] + nc * fj[2] + nd;
    const double t = di / (di - dj);
    add({fi[0] + t * (fj[0] - fi[0]), fi[1] + t * (fj[1] - fi[1]), fi[2] + t * (fj[2] - fi[2])});
  }
  return range;
}

/// A cheap answer to "do the two chords overlap with positive length?" that
/// may only err towards yes: a superfluous cut refines the piece's partition
/// without changing any classification, whereas a missed cut would be wrong.
/// Says yes when the double estimates overlap by clearly more than their
/// rounding error (2^-10 grid units against errors near 2^-26 for well-shaped
/// input); every other case goes to the exact test.
bool chords_clearly_overlap(const Polygon& piece, const std::vector<std::int8_t>& signs, const Plane& support,
                            const Polygon& other, const std::vector<std::int8_t>& other_signs) {
  const double a0 = static_cast<double>(support.a.raw()), a1 = static_cast<double>(support.b.raw()),
               a2 = static_cast<double>(support.c.raw());
  const double b0 = static_cast<double>(other.support.a.raw()), b1 = static_cast<double>(other.support.b.raw()),
               b2 = static_cast<double>(other.support.c.raw());
  std::array<double, 3> dir{a1 * b2 - a2 * b1, a2 * b0 - a0 * b2, a0 * b1 - a1 * b0};
  const double len = std::sqrt(dir[0] * dir[0] + dir[1] * dir[1] + dir[2] * dir[2]);
  if (!(len > 0) || !std::isfinite(len)) return false;
  for (double& d : dir) d /= len;
  const auto p = approx_chord(piece, signs, other.support, dir);
  const auto q = approx_chord(other, other_signs, support, dir);
  const double overlap = std::min(p[1], q[1]) - std::max(p[0], q[0]);
  return overlap > 0x1p-10;
}

/// Case C3: split the piece by the other polygon's plane if their
/// intersection segment crosses the piece's interior with positive length.
/// `other_signs` are the other polygon's vertices classified against the
/// piece's plane.
void cut_by_transverse(std::vector<Piece>& pieces, std::size_t i, const Plane& support, const Polygon& other,
                       const std::vector<std::int8_t>& other_signs, std::vector<std::int8_t>& signs,
                       std::vector<Plane>& cons) {
  const Polygon& poly = pieces[i].poly;
  bool neg = false, pos = false;
  signs.resize(poly.vertices.size());
  for (std::size_t v = 0; v < poly.vertices.size(); ++v) {
    const int s = classify(poly.vertices[v], other.support);
    signs[v] = static_cast<std::int8_t>(s);
    neg |= s < 0;
    pos |= s > 0;
  }
  if (!(neg && pos)) return;
  if (!chords_clearly_overlap(poly, signs, support, other, other_signs)) {
    cons.clear();
    chord_constraints(poly, signs, cons);
    chord_constraints(other, other_signs, cons);
    if (!line_region_has_length(support, other.support, cons)) return;
  }
  Polygon n, p;
  if (clip(poly, signs, other.support, n, p) != ClipSide::Both) return;
  pieces[i].poly = std::move(n);
  pieces.push_back({std::move(p), pieces[i].disabled});
}

/// Classifies o's vertices against a plane; false if all lie strictly on
/// one side (o cannot meet the plane).
bool touches_plane(const Polygon& o, const Plane& plane, std::vector<std::int8_t>& signs) {
  bool neg = false, pos = false, zero = false;
  signs.resize(o.vertices.size());
  for (std::size_t v = 0; v < o.vertices.size(); ++v) {
    const int s = classify(o.vertices[v], plane);
    signs[v] = static_cast<std::int8_t>(s);
    zero |= s == 0;
    neg |= s < 0;
    pos |= s > 0;
  }
  return zero || (neg && pos);
}

/// Buffers reused across the polygons of a leaf (allocation-free inner loops).
struct LeafScratch {
  std::vector<std::int8_t> other_signs, signs;
  std::vector<Plane> cons;
  Wnv w, delta;
};

/// Fills `pieces` with the enabled and disabled pieces of t.
void build_bsp(const Soup& soup, const SoupPolygon& t, const SolveContext& ctx, LeafScratch& scratch,
               std::vector<Piece>& pieces) {
  pieces.resize(1);
  pieces[0].poly = t.poly;  // reuses the capacity of the previous polygon's first piece
  pieces[0].disabled = false;
  std::vector<std::int8_t>& other_signs = scratch.other_signs;
  std::vector<std::int8_t>& signs = scratch.signs;
  std::vector<Plane>& cons = scratch.cons;
  for (const SoupPolygon& o : soup) {
    if (o.id == t.id || !boxes_overlap(t, o)) continue;
    // Two polygons of one solid operand never cross or overlap (NSI).
    if (o.operand == t.operand && ctx.solid[t.operand]) continue;
    if (!touches_plane(o.poly, t.poly.support, other_signs)) continue;
    const bool same_plane = coplanar(t.poly.support, o.poly.support);
    const std::size_t n = pieces.size();
    for (std::size_t i = 0; i < n; ++i) {
      if (pieces[i].disabled) continue;
      if (same_plane) {
        if (coplanar_overlap(pieces[i].poly, o.poly)) cut_by_coplanar(pieces, i, o.poly, o.id < t.id);
      } else {
        cut_by_transverse(pieces, i, t.poly.support, o.poly, other_signs, signs, cons);
      }
    }
  }
}

/// Traces the last segment of a classification path: from `start` along axis
/// k onto the piece's interior point x on t's plane. Adds crossings to w and
/// collects in `delta` the transition at x of every polygon containing x
/// (t and coplanar overlapping polygons), signed relative to t's orientation.
/// `side` is the side of t's plane the path arrives from.
bool trace_onto(const Soup& soup, const SoupPolygon& t, const Dyadic& start, int k, const AxisPoint& x, Wnv& w,
                Wnv& delta, int& side, std::uint32_t skip) {
  const Plane& S = t.poly.support;
  side = classify(to_point(start), S);
  if (side == 0) return false;
  const Plane pa = dyadic_axis_plane(start, k);
  const int dir = classify(x, pa);  // sign of x_k - start_k
  if (dir == 0) return false;
  const int i = (k + 1) % 3, j = (k + 2) % 3;
  const Plane l0 = dyadic_axis_plane(start, i), l1 = dyadic_axis_plane(start, j);
  const AxisLine line = axis_line(start, k);
  const Plane r0 = dir > 0 ? -pa : pa;
  const Plane r1 = side > 0 ? -S : S;

  const auto xa = approx(x);
  AxisSegment seg{line, l0, l1, r0, r1, dir, {}, {}};
  for (int a = 0; a < 3; ++a) {
    seg.lo[a] = std::min(approx_coord(start, a), xa[a]) - 1e-6;
    seg.hi[a] = std::max(approx_coord(start, a), xa[a]) + 1e-6;
  }
  delta.assign(w.size(), 0);
  delta[t.operand] += 1;
  for (const SoupPolygon& p : soup) {
    if (p.id == t.id || p.operand == skip || box_disjoint(p, seg.lo, seg.hi)) continue;
    if (coplanar(p.poly.support, S)) {
      // Meets the segment only at x (the segment is transverse to S).
      const int loc = locate(p.poly, x);
      if (loc == 0) return false;
      if (loc < 0) delta[p.operand] += same_orientation(p.poly.support, S) ? 1 : -1;
      continue;
    }
    if (!add_crossing(seg, p, w)) return false;
  }
  return true;
}

/// Deterministic pseudo-random weights for alternative interior points.
std::uint64_t mix(std::uint64_t x) {
  x += 0x9e3779b97f4a7c15ULL;
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ULL;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebULL;
  return x ^ (x >> 31);
}

/// Classifies one enabled piece of t: returns false if no valid path was
/// found (never happens for non-degenerate pieces in practice).
/// Traces from the leaf's reference point to the piece through the dyadic
/// target (u, v) on the piece's dominant axis k. False if (u, v) is not
/// strictly inside the piece's projection or the path meets something
/// degenerately.
bool classify_through(const Subproblem& pb, const SoupPolygon& t, const Polygon& f, const Dyadic& target, int k,
                      bool i_first, bool solid, Wnv& w, Wnv& delta, Wnv& w_front, Wnv& w_back) {
  const Plane& S = t.poly.support;
  AxisPoint x;
  if (!meet(axis_line(target, k), S, x) || locate(f, x) >= 0) return false;
  const int i = (k + 1) % 3, j = (k + 2) % 3;
  const std::array<int, 3> order = i_first ? std::array<int, 3>{i, j, k} : std::array<int, 3>{j, i, k};
  w = pb.ref_w;
  int side = 0;
  // A solid operand's own polygons never cross t and its winding number is
  // 0 in front of t and 1 behind: they need not be traced at all.
  const std::uint32_t skip = solid ? t.operand : kNoSkip;
  if (!trace_path(pb.soup, pb.ref, target, order, w, skip)) return false;
  if (!trace_onto(pb.soup, t, target, k, x, w, delta, side, skip)) return false;
  w_front = w;
  w_back = w;
  for (std::size_t o = 0; o < w.size(); ++o) {
    if (side > 0) {
      w_back[o] += delta[o];
    } else {
      w_front[o] -= delta[o];
    }
  }
  if (solid) {
    w_front[t.operand] = 0;
    w_back[t.operand] = 1;
  }
  return true;
}

/// Classifies one enabled piece of t. Interior guesses come from double
/// approximations first (fast, fine for all but slivers), then from exact
/// centroids of vertex triples computed by long division, which also find
/// slivers far thinner than a double can resolve at these coordinates.
bool classify_piece(const Subproblem& pb, const SoupPolygon& t, const Polygon& f, bool solid, std::uint64_t seed,
                    Wnv& w_front, Wnv& w_back, LeafScratch& scratch) {
  const Plane& S = t.poly.support;
  const int k = dominant_axis(S);
  const int i = (k + 1) % 3, j = (k + 2) % 3;
  Wnv& w = scratch.w;
  Wnv& delta = scratch.delta;
  for (int attempt = 0; attempt < 24; ++attempt) {
    // Interior guess: the centroid first, then random convex combinations.
    double ci = 0, cj = 0, total = 0;
    for (std::size_t v = 0; v < f.vertices.size(); ++v) {
      const double weight =
          attempt < 2 ? 1.0 : 0.05 + static_cast<double>(mix(seed * 131 + attempt * 17 + v) >> 11) * 0x1p-53;
      ci += weight * approx(f.vertices[v])[i];
      cj += weight * approx(f.vertices[v])[j];
      total += weight;
    }
    ci /= total;
    cj /= total;
    // Snap to the coarsest dyadic grid whose point still lies strictly inside.
    for (int s = 7 + attempt / 4; s <= kMaxDyadicShift; ++s) {
      Dyadic target = with_shift(pb.ref, std::max(s, pb.ref.shift));
      const double scale = static_cast<double>(std::int64_t{1} << target.shift);  // exact power of two
      target.num[i] = static_cast<__int128>(std::nearbyint(ci * scale));
      target.num[j] = static_cast<__int128>(std::nearbyint(cj * scale));
      AxisPoint x;
      if (!meet(axis_line(target, k), S, x) || locate(f, x) >= 0) continue;
      if (classify_through(pb, t, f, target, k, attempt % 2 == 0, solid, w, delta, w_front, w_back)) return true;
      break;  // inside but the path is degenerate: next guess
    }
  }
  // Exact centroids of vertex triples (strictly inside a convex polygon).
  const std::size_t n = f.vertices.size();
  auto coord = [](const Point& p, int a) -> const PointXYZ& { return a == 0 ? p.x : (a == 1 ? p.y : p.z); };
  for (std::size_t a = 0; a < n; ++a) {
    const std::size_t tri[3] = {a, (a + 1) % n, (a + 2) % n};  // never collinear: the piece is strictly convex
    for (int s = 7; s <= kMaxDyadicShift; s += 3) {  // 7, 10, ..., 52
      Dyadic target = with_shift(pb.ref, std::max(s, pb.ref.shift));
      const int sh = target.shift;
      for (const int axis : {i, j}) {
        // sum of floor(x_m * 2^(sh+2) / w_m) ~ 12 * centroid * 2^sh; |x/w| <= 2^26,
        // so each term is below 2^(26+54) and the sum below 2^82.
        __int128 sum = 0;
        for (const std::size_t m : tri)
          sum += floor_scaled_ratio(coord(f.vertices[m], axis), f.vertices[m].w, sh + 2);
        const __int128 q = sum >= 0 ? (sum + 6) / 12 : -((-sum + 6) / 12);
        target.num[axis] = q;
      }
      for (const bool i_first : {true, false})
        if (classify_through(pb, t, f, target, k, i_first, solid, w, delta, w_front, w_back)) return true;
    }
  }
  return false;
}

}  // namespace

bool classify_polygon(const Subproblem& pb, const SoupPolygon& t, Wnv& w_front, Wnv& w_back) {
  LeafScratch scratch;
  return classify_piece(pb, t, t.poly, false, t.id, w_front, w_back, scratch);
}

void solve_leaf(const Subproblem& pb, const SolveContext& ctx, std::vector<OutputPolygon>& out) {
  Wnv w_front, w_back;
  LeafScratch scratch;
  std::vector<Piece> pieces;
  for (const SoupPolygon& t : pb.soup) {
    build_bsp(pb.soup, t, ctx, scratch, pieces);
    for (std::size_t n = 0; n < pieces.size(); ++n) {
      if (pieces[n].disabled) continue;
      if (!classify_piece(pb, t, pieces[n].poly, ctx.solid[t.operand] != 0, (static_cast<std::uint64_t>(t.id) << 20) ^ n,
                          w_front, w_back,
                          scratch))
        throw Error("ember: could not classify a polygon piece (no non-degenerate trace path found); "
                    "this input is too degenerate for the current implementation");
      const bool in_front = ctx.inside(w_front), in_back = ctx.inside(w_back);
      if (in_front == in_back) continue;
      out.push_back({pieces[n].poly, t.id, t.operand, in_front});
    }
  }
}

}  // namespace ember::core
