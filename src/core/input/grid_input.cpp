// Operands onto the grid and the audit of the rounding (see grid_input.hpp).
#include "core/input/grid_input.hpp"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_scan.h>
#include <tbb/parallel_reduce.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdio>
#include <optional>

#include "core/support/parallel_select.hpp"
#include "core/support/sort_pairs.hpp"
#include "core/input/face_triangulation.hpp"
#include "ember/error.hpp"

namespace ember::core {

namespace {

using ld = long double;

std::array<ld, 3> cross(const Vec3d& a, const Vec3d& b, const Vec3d& c) {
  const ld ux = ld(b.x) - a.x, uy = ld(b.y) - a.y, uz = ld(b.z) - a.z;
  const ld vx = ld(c.x) - a.x, vy = ld(c.y) - a.y, vz = ld(c.z) - a.z;
  return {uy * vz - uz * vy, uz * vx - ux * vz, ux * vy - uy * vx};
}

/// The input triangle has area: its normal is not lost in the rounding of
/// the computation (|n| > 2^-40 |u||v|, so collinear corners that merely
/// print differently do not count as features).
bool has_area(const std::array<ld, 3>& n, const Vec3d& a, const Vec3d& b, const Vec3d& c) {
  const auto len2 = [](const Vec3d& p, const Vec3d& q) {
    const ld x = ld(q.x) - p.x, y = ld(q.y) - p.y, z = ld(q.z) - p.z;
    return x * x + y * y + z * z;
  };
  const ld n2 = n[0] * n[0] + n[1] * n[1] + n[2] * n[2];
  return n2 > std::ldexp(ld(1), -80) * len2(a, b) * len2(a, c);
}

/// rounding_change in double, where it is sure to agree with the long
/// double definition; nullopt where it is not (then the caller evaluates
/// that). Why it agrees: with D_u, D_v the largest |component| of u = b - a
/// and v = c - a in [2^-200, 2^200] nothing overflows and no term that
/// matters underflows; each normal component then errs by at most ~6
/// roundings of |u_i v_j| + |u_j v_i| (2^-51 of it) in double and 2^-62 in
/// long double. The area test compares |n| with 2^-40 |u||v|: a margin of
/// 2 either way is 2^11 times those errors, so both evaluations side alike.
/// The sign of n . g: each n_i errs by at most 8 roundings of D_u D_v and
/// the dot product adds 3 roundings of |n_i g_i| <= 2 D_u D_v |g_i|, in all
/// under 14 * 2^-53 D_u D_v sum |g_i| < E = 2^-47 D_u D_v sum |g_i| (the
/// long double errors are 2^-11 of that): |n . g| > E fixes the exact sign,
/// which both evaluations then give.
std::optional<int> rounding_change_filtered(const Vec3d& a, const Vec3d& b, const Vec3d& c,
                                            const std::array<std::int64_t, 3>& g) {
  const double ux = b.x - a.x, uy = b.y - a.y, uz = b.z - a.z;
  const double vx = c.x - a.x, vy = c.y - a.y, vz = c.z - a.z;
  const double du = std::max({std::fabs(ux), std::fabs(uy), std::fabs(uz)});
  const double dv = std::max({std::fabs(vx), std::fabs(vy), std::fabs(vz)});
  if (!(du >= 0x1p-200 && du <= 0x1p200 && dv >= 0x1p-200 && dv <= 0x1p200)) return std::nullopt;
  const double n[3] = {uy * vz - uz * vy, uz * vx - ux * vz, ux * vy - uy * vx};
  const double n2 = n[0] * n[0] + n[1] * n[1] + n[2] * n[2];
  const double threshold = 0x1p-80 * (ux * ux + uy * uy + uz * uz) * (vx * vx + vy * vy + vz * vz);
  if (n2 <= 0.25 * threshold) return -1;            // |n| <= 2^-41 |u||v|: no area
  if (!(n2 >= 4 * threshold)) return std::nullopt;  // near the area threshold
  if (g[0] == 0 && g[1] == 0 && g[2] == 0) return 1;
  // |g_i| < 2^53: exact in double.
  const double g0 = static_cast<double>(g[0]), g1 = static_cast<double>(g[1]), g2 = static_cast<double>(g[2]);
  const double dot = n[0] * g0 + n[1] * g1 + n[2] * g2;
  const double bound = 0x1p-47 * du * dv * (std::fabs(g0) + std::fabs(g1) + std::fabs(g2));
  if (dot > bound) return 0;
  if (dot < -bound) return 2;
  return std::nullopt;
}

}  // namespace

int rounding_change_reference(const Vec3d& a, const Vec3d& b, const Vec3d& c, const std::array<std::int64_t, 3>& g) {
  const std::array<ld, 3> n = cross(a, b, c);
  if (!has_area(n, a, b, c)) return -1;
  if (g[0] == 0 && g[1] == 0 && g[2] == 0) return 1;
  return n[0] * g[0] + n[1] * g[1] + n[2] * g[2] < 0 ? 2 : 0;
}

int rounding_change(const Vec3d& a, const Vec3d& b, const Vec3d& c, const std::array<std::int64_t, 3>& g) {
  // A long double per term is x87 code: the filter decides almost every
  // triangle in double (the audit runs on every input triangle).
  if (const std::optional<int> r = rounding_change_filtered(a, b, c, g)) return *r;
  return rounding_change_reference(a, b, c, g);
}

namespace {

/// What the grid did to an input triangle (rounding_change), given its
/// grid normal.
int rounding_change(const Mesh& m, const GridTriangle& t, const std::array<std::int64_t, 3>& normal) {
  return core::rounding_change(m.vertices[t.v[0]], m.vertices[t.v[1]], m.vertices[t.v[2]], normal);
}

/// f(o) for every operand: side by side for small inputs (side_by_side),
/// one after the other otherwise.
template <typename F>
void for_each_operand(const GridInput& gi, std::size_t operands, F&& f) {
  if (side_by_side(gi)) {
    tbb::parallel_for(std::size_t{0}, operands, f);
  } else {
    for (std::size_t o = 0; o < operands; ++o) f(o);
  }
}

std::string format_step(double step) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.3g", step);
  return buf;
}

}  // namespace

UsedVertices used_vertices(std::span<const Mesh> operands) {
  UsedVertices used(operands.size());
  // Operand by operand: each pass is parallel over the operand's indices
  // or vertices (a serial list of the used ones was a stretch of one
  // thread's work on large inputs).
  for (std::size_t o = 0; o < operands.size(); ++o) {
    const Mesh& m = operands[o];
    FillVector<std::uint8_t> is_used = parallel_filled<std::uint8_t>(m.vertices.size(), 0);
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, m.indices.size(), 4096),
                      [&](const tbb::blocked_range<std::size_t>& r) {
                        // Several faces share a vertex: every writer stores the same 1.
                        for (std::size_t i = r.begin(); i != r.end(); ++i)
                          std::atomic_ref<std::uint8_t>(is_used[m.indices[i]]).store(1, std::memory_order_relaxed);
                      });
    used[o] = parallel_indices_where(is_used.size(), [&](std::size_t v) { return is_used[v] != 0; });
  }
  return used;
}

Quantizer fit_used_vertices(std::span<const Mesh> operands, const UsedVertices& used) {
  struct Bounds {
    Vec3d lo{HUGE_VAL, HUGE_VAL, HUGE_VAL}, hi{-HUGE_VAL, -HUGE_VAL, -HUGE_VAL};
    void add(const Vec3d& p) {
      lo = {std::min(lo.x, p.x), std::min(lo.y, p.y), std::min(lo.z, p.z)};
      hi = {std::max(hi.x, p.x), std::max(hi.y, p.y), std::max(hi.z, p.z)};
    }
    void add(const Bounds& b) {
      if (b.lo.x > b.hi.x) return;  // empty (the identity): its infinities are not points
      add(b.lo);
      add(b.hi);
    }
  };
  Bounds all;
  bool any = false;
  for (std::size_t o = 0; o < operands.size(); ++o) {
    const Mesh& m = operands[o];
    const FillVector<std::uint32_t>& u = used[o];
    if (u.empty()) continue;
    any = true;
    // Min and max are exact and order-free, so the split does not matter.
    // Over the used vertices once each (not once per corner: a closed
    // mesh has about six corners per vertex), in index order.
    all.add(tbb::parallel_reduce(
        tbb::blocked_range<std::size_t>(0, u.size(), 4096), Bounds{},
        [&](const tbb::blocked_range<std::size_t>& r, Bounds b) {
          for (std::size_t i = r.begin(); i != r.end(); ++i) b.add(m.vertices[u[i]]);
          return b;
        },
        [](Bounds a, const Bounds& b) {
          a.add(b);
          return a;
        }));
  }
  return any ? Quantizer::fit_box(all.lo, all.hi) : Quantizer{};
}

namespace {

/// Lowest and highest grid coordinates, per axis.
using GridBounds = std::array<std::array<std::int64_t, 3>, 2>;
constexpr GridBounds kEmptyBounds{{{Quantizer::kLimit, Quantizer::kLimit, Quantizer::kLimit},
                                   {-Quantizer::kLimit, -Quantizer::kLimit, -Quantizer::kLimit}}};

GridBounds joined(GridBounds a, const GridBounds& b) {
  for (int k = 0; k < 3; ++k) {
    a[0][k] = std::min(a[0][k], b[0][k]);
    a[1][k] = std::max(a[1][k], b[1][k]);
  }
  return a;
}

/// Grid positions of the vertices operand m's faces use (the others stay
/// unset and are never read: they may lie outside the fitted box), and
/// their bounds.
struct GridVertices {
  FillVector<IntPoint> pos;
  std::span<const std::uint32_t> used;  ///< the used vertex indices, increasing (used_vertices)
  GridBounds bounds = kEmptyBounds;
};

/// In one parallel pass (the bounds were a serial pass of their own, and
/// the positions' value-initialization another).
GridVertices quantize_used(const Mesh& m, const Quantizer& q, std::span<const std::uint32_t> used) {
  GridVertices g;
  g.pos.resize(m.vertices.size());  // written at the used vertices below
  g.used = used;
  g.bounds = tbb::parallel_reduce(
      tbb::blocked_range<std::size_t>(0, g.used.size(), 2048), kEmptyBounds,
      [&](const tbb::blocked_range<std::size_t>& r, GridBounds b) {
        for (std::size_t i = r.begin(); i != r.end(); ++i) {
          const IntPoint p = q.quantize(m.vertices[g.used[i]]);
          g.pos[g.used[i]] = p;
          const std::int64_t c[3] = {p.x, p.y, p.z};
          for (int k = 0; k < 3; ++k) {
            b[0][k] = std::min(b[0][k], c[k]);
            b[1][k] = std::max(b[1][k], c[k]);
          }
        }
        return b;
      },
      joined);
  return g;
}

/// Welded ids of the used vertices: vertices at equal grid positions share
/// one id; ids follow the positions sorted by (x, y, z), ties by index.
/// Returns the id count. The order: a stable radix sort by x (sort_pairs;
/// the used vertices come in index order), then each run of equal x sorted
/// by (y, z, index) (sort_equal_key_runs). Runs are mostly single vertices,
/// so this is three radix passes where a second sort by (y, z) would take
/// five more (and a comparison sort of the tuples many steps per vertex).
std::size_t weld_grid_vertices(const GridVertices& g, FillVector<std::uint32_t>& id) {
  // |coordinate| <= kLimit < 2^25: offset by 2^25, each fits 27 bits.
  static_assert(Quantizer::kLimit < (std::int64_t{1} << 25), "grid coordinates + 2^25 fit 27 bits");
  const auto offset = [](std::int64_t c) { return static_cast<std::uint32_t>(c + (std::int64_t{1} << 25)); };
  const std::size_t n = g.used.size();
  FillVector<std::pair<std::uint32_t, std::uint32_t>> by_x(n);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, 4096), [&](const tbb::blocked_range<std::size_t>& r) {
    for (std::size_t i = r.begin(); i != r.end(); ++i) by_x[i] = {offset(g.pos[g.used[i]].x), g.used[i]};
  });
  sort_pairs(by_x);  // by (x, index): used is increasing
  sort_equal_key_runs(
      by_x, [&](const std::pair<std::uint32_t, std::uint32_t>& a, const std::pair<std::uint32_t, std::uint32_t>& b) {
        const IntPoint &p = g.pos[a.second], &q = g.pos[b.second];
        return p.y != q.y ? p.y < q.y : (p.z != q.z ? p.z < q.z : a.second < b.second);
      });
  // A new id wherever the position changes along that order: a parallel
  // prefix sum (a serial numbering loop over every vertex would be a
  // stretch of each operand's set-up in which the other threads wait).
  id.resize(g.pos.size());  // written at every used vertex below (the others are never read)
  const std::uint32_t last = tbb::parallel_scan(
      tbb::blocked_range<std::size_t>(0, n, 4096), std::uint32_t{0},
      [&](const tbb::blocked_range<std::size_t>& r, std::uint32_t next, bool final) {
        for (std::size_t i = r.begin(); i != r.end(); ++i) {
          next += i > 0 && !(g.pos[by_x[i].second] == g.pos[by_x[i - 1].second]);
          if (final) id[by_x[i].second] = next;
        }
        return next;
      },
      [](std::uint32_t a, std::uint32_t b) { return a + b; });
  return n == 0 ? 0 : last + 1;
}

/// Writes the n - 2 triangles of every face of operand o from `first` on.
void triangulate_faces(const Mesh& m, std::uint32_t o, const GridVertices& g, const FillVector<std::uint32_t>& id,
                       std::size_t first, GridInput& gi) {
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, m.face_count(), 1024),
                    [&](const tbb::blocked_range<std::size_t>& r) {
                      std::vector<IntPoint> corners;
                      std::vector<std::array<std::uint32_t, 3>> tris;
                      for (std::size_t f = r.begin(); f != r.end(); ++f) {
                        const auto face = m.face(f);
                        std::size_t out = first + m.face_offsets[f] - 2 * f;
                        const auto emit = [&](std::uint32_t a, std::uint32_t b, std::uint32_t c) {
                          const std::uint32_t va = face[a], vb = face[b], vc = face[c];
                          gi.triangles[out] = {{va, vb, vc}, o, static_cast<std::uint32_t>(f)};
                          gi.corners[out] = {g.pos[va], g.pos[vb], g.pos[vc]};
                          gi.vertex_ids[out] = {id[va], id[vb], id[vc]};
                          gi.normals[out] = grid_normal(g.pos[va], g.pos[vb], g.pos[vc]);
                          ++out;
                        };
                        if (face.size() == 3) {
                          emit(0, 1, 2);
                          continue;
                        }
                        corners.clear();
                        for (const std::uint32_t v : face) corners.push_back(g.pos[v]);
                        tris.clear();
                        triangulate_polygon(corners, tris);
                        for (const auto& t : tris) emit(t[0], t[1], t[2]);
                      }
                    });
}

}  // namespace

GridInput to_grid(std::span<const Mesh> operands, const Quantizer& q, const UsedVertices& used) {
  GridInput gi;
  gi.operand_begin.push_back(0);
  for (const Mesh& m : operands)  // n - 2 triangles per face of n corners
    gi.operand_begin.push_back(gi.operand_begin.back() + m.indices.size() - 2 * m.face_count());
  gi.triangles.resize(gi.operand_begin.back());
  gi.corners.resize(gi.operand_begin.back());
  gi.vertex_ids.resize(gi.operand_begin.back());
  gi.normals.resize(gi.operand_begin.back());
  // Small inputs: the operands side by side (kSideBySideTriangles). Each
  // chain writes its own slice; the box is joined after.
  gi.vertex_count.resize(operands.size());
  std::vector<GridBounds> box(operands.size(), kEmptyBounds);
  const auto chain = [&](std::size_t o) {
    const GridVertices g = quantize_used(operands[o], q, used[o]);
    box[o] = g.bounds;
    FillVector<std::uint32_t> id;
    gi.vertex_count[o] = weld_grid_vertices(g, id);
    triangulate_faces(operands[o], static_cast<std::uint32_t>(o), g, id, gi.operand_begin[o], gi);
  };
  for_each_operand(gi, operands.size(), chain);
  GridBounds all = kEmptyBounds;
  for (const GridBounds& b : box) all = joined(all, b);
  gi.lo = all[0];
  gi.hi = all[1];
  return gi;
}

void audit_quantization(std::span<const Mesh> operands, const GridInput& grid, const Quantizer& q,
                        std::vector<OperandReport>& reports, std::vector<std::string>& warnings) {
  // {with area, collapsed, flipped}: counts, so any split adds up the same.
  // Small inputs: the operands side by side (kSideBySideTriangles); the
  // reports and warnings follow in operand order.
  using Counts = std::array<std::size_t, 3>;
  std::vector<Counts> per_operand(operands.size());
  const auto count = [&](std::size_t o) {
    per_operand[o] = tbb::parallel_reduce(
        tbb::blocked_range<std::size_t>(grid.operand_begin[o], grid.operand_begin[o + 1], 4096), Counts{},
        [&](const tbb::blocked_range<std::size_t>& range, Counts c) {
          for (std::size_t i = range.begin(); i != range.end(); ++i) {
            const int change = rounding_change(operands[o], grid.triangles[i], grid.normals[i]);
            if (change < 0) continue;
            ++c[0];
            if (change > 0) ++c[change];
          }
          return c;
        },
        [](Counts a, const Counts& b) {
          return Counts{a[0] + b[0], a[1] + b[1], a[2] + b[2]};
        });
  };
  for_each_operand(grid, operands.size(), count);
  for (std::size_t o = 0; o < operands.size(); ++o) {
    OperandReport& r = reports[o];
    const Counts& counts = per_operand[o];
    const std::size_t with_area = counts[0];
    r.collapsed_triangles = counts[1];
    r.flipped_triangles = counts[2];
    r.triangles = grid.operand_begin[o + 1] - grid.operand_begin[o];
    const std::size_t changed = r.collapsed_triangles + r.flipped_triangles;
    if (changed == 0) continue;
    const std::string what = std::to_string(r.collapsed_triangles) + " of its " + std::to_string(with_area) +
                             " triangles collapse and " + std::to_string(r.flipped_triangles) +
                             " flip on the quantization grid (step " + format_step(q.grid_spacing()) +
                             "; 2^26 steps span the bounding box of all operands together)";
    // Most of the operand gone or inverted: the result would not be the
    // Boolean of the given shapes, so refuse rather than answer wrongly.
    if (2 * changed > with_area)
      throw Error(what +
                      "; most of the operand is lost on the grid, so the result would not be the Boolean of the given "
                      "shapes. It is thinner than the step or too small beside the other operands: remove far-away or "
                      "huge geometry, or scale the operands to similar sizes",
                  {.operand = o});
    warnings.push_back("operand " + std::to_string(o) + ": " + what + "; features finer than the step are lost");
  }
}

}  // namespace ember::core
