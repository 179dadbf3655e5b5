// The direct route's work on one touched triangle (direct_faces.hpp; the
// argument is in direct_mesh.hpp).
#include "core/route/direct/direct_faces.hpp"

#include <algorithm>
#include <cassert>

namespace ember::core {

using i128 = __int128;

namespace {

int sign_of(i128 v) { return (v > 0) - (v < 0); }

}  // namespace

Point crossing_point(const IntPoint& a, const IntPoint& b, i128 sa, i128 sb) {
  // (a (-sb) + b sa) / (sa - sb) with |sa|, |sb| < 2^83 and |a|, |b| <= 2^25:
  // each product is below 2^108 and each sum below 2^109, so the numerators
  // are plain i128 arithmetic (as Int<83> x Int<26> products: ~3x the
  // instructions; every crossing is computed by the three triangles that
  // hold it).
  static_assert(PointXYZ::bits >= 110 && PointW::bits >= 84, "crossing points fit Point");
  static_assert(kCoordLimit <= (std::int64_t{1} << 25), "products below 2^108");
  [[maybe_unused]] constexpr i128 kSideLimit = i128{1} << 83;
  assert(sa > -kSideLimit && sa < kSideLimit && sb > -kSideLimit && sb < kSideLimit);
  i128 ka = -sb, kb = sa, w = sa - sb;
  if (w < 0) ka = -ka, kb = -kb, w = -w;
  const i128 x = ka * a.x + kb * b.x, y = ka * a.y + kb * b.y, z = ka * a.z + kb * b.z;
  Point p{PointXYZ(x), PointXYZ(y), PointXYZ(z), PointW(w), {}};
  // The cached approximation from the i128 values (three roundings each, one
  // in the division: within the 8 units in the last place Point::f allows),
  // not from the three-limb Points (~200 more instructions per crossing).
  const double dw = approx_to_double(w);
  p.f = {approx_to_double(x) / dw, approx_to_double(y) / dw, approx_to_double(z) / dw};
  return p;
}

bool crossing_before(i128 xa, i128 xb, i128 ya, i128 yb) {
  // |sa| / |sa - sb| compared by cross-multiplication: below 2^83 * 2^84.
  const auto mag = [](i128 v) { return v < 0 ? -v : v; };
  return Int<83>(mag(xa)) * Int<84>(mag(ya - yb)) < Int<83>(mag(ya)) * Int<84>(mag(xa - xb));
}

bool pair_chord(const GridTriangles& grid, const EdgeNames& names, std::uint32_t x, std::uint32_t y, PairChord& out) {
  const std::array<IntPoint, 3>&c = grid.corners[x], &d = grid.corners[y];
  const std::array<std::int64_t, 3>&n = grid.normals[x], &nf = grid.normals[y];
  i128 st[3], sf[3];  // x's corners against y's plane, y's against x's
  for (int i = 0; i < 3; ++i) {
    st[i] = grid_side(d[0], nf, c[i]);
    sf[i] = grid_side(c[0], n, d[i]);
    if (st[i] == 0 || sf[i] == 0) return false;  // a corner on the other's plane
  }
  // Each triangle's lone corner on its side of the other's plane; none when
  // one lies wholly beside the other's plane (they do not meet; the partner
  // search passes no such pair).
  const auto lone_corner = [](const i128* v) {
    constexpr int kLone[8] = {-1, 0, 1, 2, 2, 1, 0, -1};  // by the corners' side bits
    return kLone[(v[0] > 0) | (v[1] > 0) << 1 | (v[2] > 0) << 2];
  };
  const int lone_x = lone_corner(st), lone_y = lone_corner(sf);
  if (lone_x < 0 || lone_y < 0) return false;
  int found = 0;
  bool leaves_along_d[2];
  // An edge p -> q of one triangle that crosses the other's plane meets the
  // line L of both planes at a point P; the other triangle meets L in the
  // stretch between its two edges that cross this plane, r -> s and t -> r
  // from its lone corner r. P lies inside the other triangle iff p -> q turns
  // the same way around those two edges (orient3d); P is on L, which never
  // reaches the wedge opposite r's, so the third edge's test adds nothing
  // (it cost a third of the orientations). A zero means P is on one of the
  // two edges: not general position.
  //   orient3d(p, q, r, s) = m . (s - p) and orient3d(p, q, t, r) =
  //   -m . (t - p) with m = (q - p) x (r - p): one cross product for both
  //   (differences < 2^26: m < 2^53 in int64, each dot product < 2^81).
  static_assert(kCoordLimit <= (std::int64_t{1} << 25) && 2 * 26 + 1 < 63 && 53 + 26 + 2 < 127,
                "pair chord orientations: differences < 2^26, m < 2^53 in int64, three-term dots < 2^81");
  const auto crossing = [&](const IntPoint& p, const IntPoint& q, const std::array<IntPoint, 3>& other, int lone,
                            int& inside) {
    const IntPoint &r = other[static_cast<std::size_t>(lone)], &sv = other[static_cast<std::size_t>((lone + 1) % 3)],
                   &t = other[static_cast<std::size_t>((lone + 2) % 3)];
    const std::int64_t ux = q.x - p.x, uy = q.y - p.y, uz = q.z - p.z;
    const std::int64_t vx = r.x - p.x, vy = r.y - p.y, vz = r.z - p.z;
    const std::int64_t mx = uy * vz - uz * vy, my = uz * vx - ux * vz, mz = ux * vy - uy * vx;
    const auto dot = [&](const IntPoint& e) {
      return i128{mx} * (e.x - p.x) + i128{my} * (e.y - p.y) + i128{mz} * (e.z - p.z);
    };
    const int o_rs = sign_of(dot(sv)), o_tr = -sign_of(dot(t));
    if (o_rs == 0 || o_tr == 0) return false;
    inside = o_rs == o_tr;
    return true;
  };
  // The end points on x's edges (crossing y), then on y's (crossing x).
  // d = n_x x n_y points into x from x's edge i -> j iff n_y . (c_j - c_i)
  // > 0, and into y from y's edge i -> j iff n_x . (d_j - d_i) < 0.
  for (const bool on_x : {true, false}) {
    const std::array<IntPoint, 3>& e = on_x ? c : d;
    const i128* s = on_x ? st : sf;
    for (int i = 0; i < 3; ++i) {
      const int j = i == 2 ? 0 : i + 1;
      if ((s[i] > 0) == (s[j] > 0)) continue;
      int inside = 0;
      if (!crossing(e[i], e[j], on_x ? d : c, on_x ? lone_y : lone_x, inside)) return false;
      if (!inside) continue;
      if (found == 2) return false;
      ChordEnd& end = out.end[static_cast<std::size_t>(found)];
      end.name = on_x ? CrossingName{names.edge_key(x, i), y} : CrossingName{names.edge_key(y, i), x};
      end.sa = s[i], end.sb = s[j];
      end.edge = static_cast<std::uint8_t>(i);
      end.on_y = !on_x;
      leaves_along_d[found++] = on_x ? s[j] > 0 : s[j] < 0;
    }
  }
  if (found != 2 || leaves_along_d[0] == leaves_along_d[1]) return false;
  if (leaves_along_d[1]) std::swap(out.end[0], out.end[1]);  // end[0]: the start, from which the chord runs along d
  return true;
}

void TriangleCutter::add_chord(const ChordRef& r) {
  const int base = static_cast<int>(cross_.size());
  for (const ChordEnd& e : r.chord->end) {
    Crossing& x = cross_.emplace_back();
    x.name = e.name;
    x.tri = e.on_y ? r.y : r.x;
    x.tri_edge = e.edge;
    x.sa = e.sa, x.sb = e.sb;
    if (e.on_y == r.reversed) x.edge = e.edge;  // on this triangle's own edge
  }
  // Seen from y, n_y x n_x reverses the chord.
  const int from = base + (r.reversed ? 1 : 0), to = base + (r.reversed ? 0 : 1);
  cross_[static_cast<std::size_t>(from)].next = to;
  cross_[static_cast<std::size_t>(to)].prev = from;
}

bool TriangleCutter::merge_equal_names() {
  const std::size_t n = cross_.size();
  order_.resize(n);
  for (std::uint32_t k = 0; k < n; ++k) order_[k] = k;
  const auto name_before = [&](std::uint32_t a, std::uint32_t b) {
    return cross_[a].name != cross_[b].name ? cross_[a].name < cross_[b].name : a < b;
  };
  if (n > 16) {
    std::sort(order_.begin(), order_.end(), name_before);
  } else {  // most triangles have a few crossings: std::sort's set-up was most of the work
    for (std::size_t i = 1; i < n; ++i) {
      const std::uint32_t k = order_[i];
      std::size_t at = i;
      for (; at > 0 && name_before(k, order_[at - 1]); --at) order_[at] = order_[at - 1];
      order_[at] = k;
    }
  }
  merged_.clear();
  merged_at_.resize(n);
  for (const std::uint32_t k : order_) {
    if (merged_.empty() || merged_.back().name != cross_[k].name) {
      merged_.push_back(cross_[k]);
      merged_.back().next = merged_.back().prev = -1;
    }
    merged_at_[k] = static_cast<std::uint32_t>(merged_.size() - 1);
  }
  for (std::size_t k = 0; k < n; ++k) {
    if (cross_[k].next < 0) continue;
    const std::uint32_t a = merged_at_[k], b = merged_at_[static_cast<std::size_t>(cross_[k].next)];
    if (merged_[a].next >= 0 || merged_[b].prev >= 0) return false;  // an edge shared by more than two
    merged_[a].next = static_cast<int>(b);
    merged_[b].prev = static_cast<int>(a);
  }
  cross_.swap(merged_);
  return true;
}

bool TriangleCutter::before(const Crossing& x, const Crossing& y) const {
  return crossing_before(x.sa, x.sb, y.sa, y.sb);
}

bool TriangleCutter::walk_faces(std::uint32_t id, const std::array<IntPoint, 3>& c, CutFaces& out) {
  const std::size_t m = cross_.size();
  ring_.clear();
  for (int k = 0; k < 3; ++k) {
    ring_.push_back(static_cast<std::uint32_t>(k));
    const std::size_t first = ring_.size();
    for (std::size_t i = 0; i < m; ++i)
      if (cross_[i].edge == k) ring_.push_back(kCorners + static_cast<std::uint32_t>(i));
    std::sort(ring_.begin() + static_cast<std::ptrdiff_t>(first), ring_.end(),
              [&](std::uint32_t x, std::uint32_t y) { return before(cross_[x - kCorners], cross_[y - kCorners]); });
    for (std::size_t s = first + 1; s < ring_.size(); ++s)  // two planes through one point of the edge
      if (!before(cross_[ring_[s - 1] - kCorners], cross_[ring_[s] - kCorners])) return false;
  }
  const std::size_t r = ring_.size();
  slot_.assign(m, 0);
  for (std::size_t s = 0; s < r; ++s)
    if (ring_[s] >= kCorners) slot_[ring_[s] - kCorners] = static_cast<std::uint32_t>(s);
  arc_used_.assign(r, 0);
  visited_.assign(m, 0);
  face_count_ = 0;
  for (std::size_t start = 0; start < r; ++start) {
    if (arc_used_[start]) continue;
    Face& face = next_face();
    std::size_t s = start, steps = 0;
    do {
      if (arc_used_[s] || ++steps > r) return false;
      arc_used_[s] = 1;
      face.loop.push_back(ring_[s]);
      const std::uint32_t y = ring_[(s + 1) % r];
      if (y < kCorners) {
        s = (s + 1) % r;
        continue;
      }
      // Along y's polyline to its other end on the boundary: forwards (the
      // inside of the other solid on the left) when y is where it starts.
      std::uint32_t x = y - kCorners;
      const bool forward = cross_[x].next >= 0;
      if (!face.agree(forward)) return false;
      face.loop.push_back(y);
      for (std::size_t hops = 0;; ++hops) {
        if (hops > m) return false;
        x = static_cast<std::uint32_t>(forward ? cross_[x].next : cross_[x].prev);
        visited_[x] = 1;
        if (cross_[x].edge >= 0) break;
        face.loop.push_back(kCorners + x);
      }
      s = slot_[x];
    } while (s != start);
  }
  for (std::uint32_t k = 0; k < kCorners; ++k) local_.exact[k] = to_point(c[k]);  // the crossings follow (cut)
  const Plane support = *supporting_plane(c[0], c[1], c[2]);
  if (!add_closed_curves(support)) return false;
  const std::uint32_t name_base = static_cast<std::uint32_t>(out.names.size());
  if (!emit_faces(id, support, name_base, out)) return false;
  for (std::size_t i = 0; i < m; ++i) {
    out.names.push_back(cross_[i].name);
    out.points.push_back(local_.exact[kCorners + i]);
  }
  return true;
}

bool TriangleCutter::add_closed_curves(const Plane& support) {
  const std::size_t boundary_faces = face_count_;
  loops_.clear();
  for (std::size_t i = 0; i < cross_.size(); ++i) {
    if (visited_[i]) continue;
    std::vector<std::uint32_t> curve;
    std::size_t x = i;
    do {  // forwards round the curve: interior crossings have both links
      if (visited_[x] || cross_[x].edge >= 0 || cross_[x].next < 0) return false;
      visited_[x] = 1;
      curve.push_back(kCorners + static_cast<std::uint32_t>(x));
      x = static_cast<std::size_t>(cross_[x].next);
    } while (x != i);
    loops_.push_back(std::move(curve));
  }
  if (loops_.empty()) return true;
  // Each closed curve, run forwards, has the inside of the other solid on
  // its left: counter-clockwise, its inside is a face with w = 1 and a hole
  // with w = 0 around it; clockwise, the reverse.
  const std::size_t n = loops_.size();
  std::vector<int> turn(n);
  for (std::size_t i = 0; i < n; ++i)
    if ((turn[i] = loop_orientation_in_plane(loops_[i], support, local_)) == 0) return false;
  // Nesting: the curves around each curve's first point.
  std::vector<std::vector<std::uint32_t>> around(n);
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = 0; j < n; ++j) {
      if (i == j) continue;
      const int where = locate_in_loop(loops_[j], loops_[i][0], support, local_);
      if (where < 0) return false;
      if (where == 1) around[i].push_back(static_cast<std::uint32_t>(j));
    }
  // One face inside each curve (its loop counter-clockwise).
  std::vector<std::size_t> inner(n);
  for (std::size_t i = 0; i < n; ++i) {
    inner[i] = face_count_;
    Face& f = next_face();
    f.loop = loops_[i];
    if (turn[i] < 0) std::reverse(f.loop.begin(), f.loop.end());
    f.w = turn[i] > 0;
  }
  for (std::size_t i = 0; i < n; ++i) {
    // The face that holds curve i: inside the innermost curve around it,
    // else the boundary face whose loop holds its first point.
    std::size_t holder = SIZE_MAX;
    for (const std::uint32_t j : around[i])
      if (around[j].size() + 1 == around[i].size()) holder = inner[j];
    if (around[i].empty()) {
      for (std::size_t f = 0; f < boundary_faces && holder == SIZE_MAX; ++f) {
        const int where = boundary_faces == 1 ? 1 : locate_in_loop(faces_[f].loop, loops_[i][0], support, local_);
        if (where < 0) return false;
        if (where == 1) holder = f;
      }
    }
    if (holder == SIZE_MAX) return false;
    Face& f = faces_[holder];
    if (!f.agree(turn[i] < 0)) return false;  // outside a curve w is 0 if it turns counter-clockwise
    f.holes.push_back(loops_[i]);
    if (turn[i] > 0) std::reverse(f.holes.back().begin(), f.holes.back().end());  // holes run clockwise
  }
  return true;
}

bool TriangleCutter::emit_faces(std::uint32_t id, const Plane& support, std::uint32_t name_base, CutFaces& out) {
  const std::uint32_t o = operand_of_[id];
  for (std::size_t i = 0; i < face_count_; ++i) {
    Face& face = faces_[i];
    if (face.w < 0) return false;  // a face no curve reaches: t was not cut
    // t's own operand is 0 in front of t and 1 behind it; the other one's is w on both sides.
    front_[o] = 0, back_[o] = 1, front_[1 - o] = back_[1 - o] = face.w;
    const bool in_front = ctx_.inside(front_), in_back = ctx_.inside(back_);
    if (in_front == in_back) continue;
    ++out.faces;
    tris_.clear();
    if (!face.holes.empty()) {
      if (!triangulate_with_holes(face.loop, face.holes, support, local_, tris_)) return false;
    } else if (face.loop.size() == 3) {
      tris_.push_back({face.loop[0], face.loop[1], face.loop[2]});
    } else if (!triangulate_loop(face.loop, support, local_, tris_)) {
      return false;
    }
    for (std::array<std::uint32_t, 3> t : tris_) {
      if (in_front) std::swap(t[1], t[2]);  // emitted reversed: the result lies in front
      for (std::uint32_t& v : t)
        if (v >= kCorners) v = kCorners + name_base + (v - kCorners);
      out.tris.push_back(t);
      out.source.push_back(id);
    }
  }
  return true;
}

}  // namespace ember::core
