// Embedded vertex stars (see vertex_stars.hpp for the argument).
#include "core/vertex_stars.hpp"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_reduce.h>

#include <algorithm>
#include <atomic>
#include <numeric>
#include <vector>

namespace ember::core {

namespace {

using i128 = __int128;
static_assert(kCoordLimit <= (std::int64_t{1} << 25) && kMaxValence <= 1024,
              "bits: normals < 2^53, |d| < 2^10 * 2^53 = 2^63 (int64), d . n < 3 * 2^116, s < 2^90, e . s < 3 * 2^116");

/// One triangle of a star, seen from the star's vertex v: (v, a, b)
/// counter-clockwise around its normal n. The a ids are kept apart
/// (Scratch::start), where the walk below scans them.
struct Spoke {
  std::uint32_t b = 0;            ///< welded id of the corner after a
  std::array<std::int64_t, 3> e;  ///< a - v
  const std::array<std::int64_t, 3>* n = nullptr;
};

/// Per worker: a star's spokes, grown to the largest valence seen and
/// written by index (no per-spoke push_back).
struct Scratch {
  std::vector<Spoke> spokes;
  std::vector<std::uint32_t> start;  ///< per spoke: the welded id of its a
};

/// Whether the star given by `corners` (3 * triangle + corner, all at one
/// vertex) is certified.
bool star_is_embedded(std::span<const ContactTriangle> tris, std::span<const std::uint32_t> corners, Scratch& sc) {
  const std::size_t m = corners.size();
  if (m < 3 || m > kMaxValence) return false;
  if (sc.spokes.size() < m) {
    sc.spokes.resize(m);
    sc.start.resize(m);
  }
  Spoke* const spokes = sc.spokes.data();
  std::uint32_t* const start = sc.start.data();
  std::array<std::int64_t, 3> d{0, 0, 0};  // |d| < 2^10 * 2^53 = 2^63
  for (std::size_t i = 0; i < m; ++i) {
    const std::uint32_t c = corners[i];
    const ContactTriangle& t = tris[c / 3];
    const int k = static_cast<int>(c % 3), k1 = k == 2 ? 0 : k + 1, k2 = k1 == 2 ? 0 : k1 + 1;
    const IntPoint &v = t.p()[k], &a = t.p()[k1];
    start[i] = t.id[k1];
    spokes[i] = {t.id[k2], {a.x - v.x, a.y - v.y, a.z - v.z}, &t.n};
    for (int j = 0; j < 3; ++j) d[j] += t.n[j];
  }
  for (std::size_t i = 0; i < m; ++i) {
    const std::array<std::int64_t, 3>& n = *spokes[i].n;
    if (i128(d[0]) * n[0] + i128(d[1]) * n[1] + i128(d[2]) * n[2] <= 0) return false;
  }
  // Walk the spokes from spoke 0, each to the one starting where it ends
  // (a_next = b), m steps: back at spoke 0 after winding once. A walk that
  // returns to spoke 0 early goes round again (a second turn: the halves
  // below see it), one that runs into a loop without spoke 0 never returns.
  const std::array<std::int64_t, 3>& e0 = spokes[0].e;
  const std::array<i128, 3> s{i128(d[1]) * e0[2] - i128(d[2]) * e0[1], i128(d[2]) * e0[0] - i128(d[0]) * e0[2],
                              i128(d[0]) * e0[1] - i128(d[1]) * e0[0]};
  // Halves: upper (0, pi), lower [pi, 2 pi] (e_0 itself is angle 0).
  bool lower = false;
  std::size_t i = 0;
  for (std::size_t step = 1; step <= m; ++step) {
    const std::uint32_t b = spokes[i].b;
    std::size_t next = 0;
    while (next < m && start[next] != b) ++next;
    if (next == m) return false;  // b is no spoke's start: the star is open
    if (step == m) return next == 0;
    i = next;
    const std::array<std::int64_t, 3>& e = spokes[i].e;
    // e . s = 0: e's projection is parallel to e_0's, at pi or at a full
    // turn, both in the closed lower half.
    const bool upper = e[0] * s[0] + e[1] * s[1] + e[2] * s[2] > 0;
    if (upper && lower) return false;  // lower -> upper: past angle 0, a second turn
    lower |= !upper;
  }
  return false;  // not reached: the loop returns at step m
}

}  // namespace

void certify_embedded_stars(std::span<ContactTriangle> tris) {
  const std::size_t n = tris.size();
  if (n == 0) return;
  const std::uint32_t vertices =
      1 + tbb::parallel_reduce(
              tbb::blocked_range<std::size_t>(0, n, 4096), std::uint32_t{0},
              [&](const tbb::blocked_range<std::size_t>& r, std::uint32_t top) {
                for (std::size_t t = r.begin(); t != r.end(); ++t)
                  top = std::max({top, tris[t].id[0], tris[t].id[1], tris[t].id[2]});
                return top;
              },
              [](std::uint32_t x, std::uint32_t y) { return std::max(x, y); });
  // The corners at each vertex (3 * triangle + k), grouped by vertex. Their
  // order within a vertex depends on the schedule; the certificate does not.
  std::vector<std::uint32_t> start(static_cast<std::size_t>(vertices) + 1, 0);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, 4096), [&](const tbb::blocked_range<std::size_t>& r) {
    for (std::size_t t = r.begin(); t != r.end(); ++t)
      for (const std::uint32_t id : tris[t].id)
        std::atomic_ref<std::uint32_t>(start[id + 1]).fetch_add(1, std::memory_order_relaxed);
  });
  std::inclusive_scan(start.begin(), start.end(), start.begin());
  std::vector<std::uint32_t> fill(start.begin(), start.end() - 1), corners(3 * n);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, 4096), [&](const tbb::blocked_range<std::size_t>& r) {
    for (std::size_t t = r.begin(); t != r.end(); ++t)
      for (std::uint32_t k = 0; k < 3; ++k) {
        const std::uint32_t at = std::atomic_ref<std::uint32_t>(fill[tris[t].id[k]]).fetch_add(1, std::memory_order_relaxed);
        corners[at] = static_cast<std::uint32_t>(3 * t + k);
      }
  });
  fill = {};
  std::vector<char> embedded(vertices, 0);
  // ~1,300 instructions per star: 128 of them are a task worth stealing.
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, vertices, 128), [&](const tbb::blocked_range<std::size_t>& r) {
    Scratch scratch;
    for (std::size_t v = r.begin(); v != r.end(); ++v)
      embedded[v] = star_is_embedded(
          tris, std::span<const std::uint32_t>(corners.data() + start[v], start[v + 1] - start[v]), scratch);
  });
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, 4096), [&](const tbb::blocked_range<std::size_t>& r) {
    for (std::size_t t = r.begin(); t != r.end(); ++t) {
      std::uint8_t mask = 0;
      for (int k = 0; k < 3; ++k) mask |= static_cast<std::uint8_t>(embedded[tris[t].id[k]] << k);
      tris[t].embedded = mask;
    }
  });
}

}  // namespace ember::core
