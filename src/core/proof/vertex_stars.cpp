// Embedded vertex stars (see vertex_stars.hpp for the argument).
#include "core/proof/vertex_stars.hpp"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_reduce.h>

#include <algorithm>
#include <atomic>
#include <vector>

namespace ember::core {

namespace {

using i128 = __int128;
static_assert(kCoordLimit <= (std::int64_t{1} << 25) && kMaxValence <= 1024,
              "bits: normals < 2^53, |d| < 2^10 * 2^53 = 2^63 (int64), d . n < 3 * 2^116, e_0 x e < 2^53, "
              "d . (e_0 x e) < 3 * 2^116");

/// One triangle of a star, seen from the star's vertex v: (v, a, b)
/// counter-clockwise around its normal n.
struct Spoke {
  std::array<std::int64_t, 3> e;  ///< a - v
  const std::array<std::int64_t, 3>* n = nullptr;
};

/// The corner of triangle t (index into tris) at vertex id v, or -1.
int corner_at(const ContactTriangle& t, std::uint32_t v) {
  return t.id[0] == v ? 0 : (t.id[1] == v ? 1 : (t.id[2] == v ? 2 : -1));
}

/// Whether the star of the vertex at corner k of triangle t, which has
/// `valence` corners in all, is certified. The walk goes from each triangle
/// (v, a, b) to its neighbour across (b, v), which has v and then b: the
/// next spoke starts where this one ends. It must come back to t after
/// exactly `valence` steps: earlier, or never, means v has another fan or an
/// open or non-manifold edge.
bool star_is_embedded(std::span<const ContactTriangle> tris, std::span<const std::array<std::uint32_t, 3>> neighbours,
                      std::uint32_t first_id, std::uint32_t t0, int k0, std::size_t valence,
                      std::vector<Spoke>& spokes) {
  if (valence < 3 || valence > kMaxValence) return false;
  spokes.resize(std::max(spokes.size(), valence));
  const std::uint32_t v = tris[t0].id[k0];
  std::array<std::int64_t, 3> d{0, 0, 0};  // |d| < 2^10 * 2^53 = 2^63
  std::uint32_t t = t0;
  int k = k0;
  for (std::size_t i = 0; i < valence; ++i) {
    if (i > 0 && t == t0) return false;  // back early: another fan at v
    const ContactTriangle& tri = tris[t];
    const IntPoint &p = tri.p()[k], &a = tri.p()[k == 2 ? 0 : k + 1];
    spokes[i] = {{a.x - p.x, a.y - p.y, a.z - p.z}, &tri.n};
    for (int j = 0; j < 3; ++j) d[j] += tri.n[j];
    // Across edge (b, v): edge k + 2 runs from corner k + 2 to corner k.
    const std::uint32_t across = neighbours[t][k == 0 ? 2 : k - 1];
    if (across == kNoNeighbor || across - first_id >= tris.size()) return false;
    const std::uint32_t next = across - first_id;
    if ((k = corner_at(tris[next], v)) < 0) return false;
    t = next;
  }
  if (t != t0) return false;  // the walk runs on: more triangles than corners in the cycle
  // Every normal on d's side, and the spokes once around d: one pass.
  // Halves: upper (0, pi), lower [pi, 2 pi], with e_0 at angle 0; e is in
  // the upper one iff d . (e_0 x e) > 0 (e_0 x e: differences < 2^26, so
  // each component < 2^53 fits int64, and every product is one 64 x 64-bit
  // multiplication).
  const std::array<std::int64_t, 3>& e0 = spokes[0].e;
  bool lower = false;
  for (std::size_t i = 0; i < valence; ++i) {
    const std::array<std::int64_t, 3>& n = *spokes[i].n;
    if (i128(d[0]) * n[0] + i128(d[1]) * n[1] + i128(d[2]) * n[2] <= 0) return false;
    if (i == 0) continue;
    const std::array<std::int64_t, 3>& e = spokes[i].e;
    const std::int64_t c0 = e0[1] * e[2] - e0[2] * e[1], c1 = e0[2] * e[0] - e0[0] * e[2],
                       c2 = e0[0] * e[1] - e0[1] * e[0];
    // d . (e_0 x e) = 0: e's projection is parallel to e_0's, at pi or at a
    // full turn, both in the closed lower half.
    const bool upper = i128(d[0]) * c0 + i128(d[1]) * c1 + i128(d[2]) * c2 > 0;
    if (upper && lower) return false;  // lower -> upper: past angle 0, a second turn
    lower |= !upper;
  }
  return true;
}

}  // namespace

void certify_embedded_stars(std::span<ContactTriangle> tris, std::span<const std::array<std::uint32_t, 3>> neighbours,
                            std::uint32_t first_id) {
  const std::size_t n = tris.size();
  if (n == 0 || neighbours.size() != n) return;
  const std::uint32_t vertices = 1 + tbb::parallel_reduce(
                                         tbb::blocked_range<std::size_t>(0, n, 4096), std::uint32_t{0},
                                         [&](const tbb::blocked_range<std::size_t>& r, std::uint32_t top) {
                                           for (std::size_t t = r.begin(); t != r.end(); ++t)
                                             top = std::max({top, tris[t].id[0], tris[t].id[1], tris[t].id[2]});
                                           return top;
                                         },
                                         [](std::uint32_t x, std::uint32_t y) { return std::max(x, y); });
  // Per vertex: its number of corners, and one of them (3 * triangle + k).
  // Which one depends on the schedule; the certificate does not (the walk
  // from any corner of a cycle meets the same cycle, and its winding number
  // does not depend on where it starts).
  std::vector<std::uint32_t> valence(vertices, 0), some(vertices, 0);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, 4096), [&](const tbb::blocked_range<std::size_t>& r) {
    for (std::size_t t = r.begin(); t != r.end(); ++t)
      for (std::uint32_t k = 0; k < 3; ++k) {
        const std::uint32_t id = tris[t].id[k];
        std::atomic_ref<std::uint32_t>(valence[id]).fetch_add(1, std::memory_order_relaxed);
        std::atomic_ref<std::uint32_t>(some[id]).store(static_cast<std::uint32_t>(3 * t + k),
                                                       std::memory_order_relaxed);
      }
  });
  std::vector<char> embedded(vertices, 0);
  // A few hundred instructions per star: 256 of them are a task worth stealing.
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, vertices, 256), [&](const tbb::blocked_range<std::size_t>& r) {
    std::vector<Spoke> spokes;
    for (std::size_t v = r.begin(); v != r.end(); ++v)
      embedded[v] = valence[v] > 0 && star_is_embedded(tris, neighbours, first_id, some[v] / 3,
                                                       static_cast<int>(some[v] % 3), valence[v], spokes);
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
