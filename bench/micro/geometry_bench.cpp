// Micro-benchmarks of the plane-based geometry kernel: classify (grid and
// homogeneous points), three-plane intersection and triangle clipping. Inputs
// are arrays of varied random data (fixed seeds) cycled through, so branch
// prediction cannot learn a single case.
#include <benchmark/benchmark.h>

#include <random>
#include <vector>

#include "geometry/geometry.hpp"

namespace {

using namespace ember;

constexpr std::size_t kCount = 4096;  // power of two: cheap index wrap

std::int64_t rand_coord(std::mt19937_64& rng) {
  return std::uniform_int_distribution<std::int64_t>(-kCoordLimit, kCoordLimit)(rng);
}
IntPoint rand_point(std::mt19937_64& rng) { return {rand_coord(rng), rand_coord(rng), rand_coord(rng)}; }
Plane rand_support(std::mt19937_64& rng) {
  for (;;)
    if (auto p = supporting_plane(rand_point(rng), rand_point(rng), rand_point(rng))) return *p;
}

/// Triangles with their vertices in a box of side 2^12 around random centers
/// (realistic mesh triangles: small relative to the full range).
std::vector<Polygon> rand_triangles(std::mt19937_64& rng) {
  std::vector<Polygon> out;
  while (out.size() < kCount) {
    const IntPoint c = rand_point(rng);
    auto near = [&] {
      std::uniform_int_distribution<std::int64_t> d(-2048, 2048);
      auto clampc = [](std::int64_t v) { return std::clamp(v, -kCoordLimit, kCoordLimit); };
      return IntPoint{clampc(c.x + d(rng)), clampc(c.y + d(rng)), clampc(c.z + d(rng))};
    };
    if (auto t = make_triangle(near(), near(), near())) out.push_back(*t);
  }
  return out;
}

void BM_ClassifyIntPoint(benchmark::State& state) {
  std::mt19937_64 rng(1);
  std::vector<IntPoint> pts;
  std::vector<Plane> planes;
  for (std::size_t i = 0; i < kCount; ++i) pts.push_back(rand_point(rng)), planes.push_back(rand_support(rng));
  std::size_t i = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(classify(pts[i], planes[(i * 7) & (kCount - 1)]));
    i = (i + 1) & (kCount - 1);
  }
}
BENCHMARK(BM_ClassifyIntPoint);

void BM_ClassifyPointSSS(benchmark::State& state) {
  std::mt19937_64 rng(2);
  std::vector<Point> pts;
  std::vector<Plane> planes;
  while (pts.size() < kCount)
    if (auto x = intersect(rand_support(rng), rand_support(rng), rand_support(rng))) pts.push_back(*x);
  for (std::size_t i = 0; i < kCount; ++i) planes.push_back(rand_support(rng));
  std::size_t i = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(classify(pts[i], planes[(i * 7) & (kCount - 1)]));
    i = (i + 1) & (kCount - 1);
  }
}
BENCHMARK(BM_ClassifyPointSSS);

void BM_IntersectSSS(benchmark::State& state) {
  std::mt19937_64 rng(3);
  std::vector<Plane> planes;
  for (std::size_t i = 0; i < kCount; ++i) planes.push_back(rand_support(rng));
  std::size_t i = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(intersect(planes[i], planes[(i + 1) & (kCount - 1)], planes[(i + 2) & (kCount - 1)]));
    i = (i + 1) & (kCount - 1);
  }
}
BENCHMARK(BM_IntersectSSS);

/// Clip by an axis plane through the middle of each triangle's extent (always
/// cuts) or just outside it (never cuts).
void clip_bench(benchmark::State& state, bool cutting) {
  std::mt19937_64 rng(4);
  const std::vector<Polygon> tris = rand_triangles(rng);
  std::vector<Plane> splits;
  for (const Polygon& t : tris) {
    const int axis = static_cast<int>(rng() % 3);
    double lo = 1e300, hi = -1e300;
    for (const Point& v : t.vertices) lo = std::min(lo, approx(v)[axis]), hi = std::max(hi, approx(v)[axis]);
    const auto pos = static_cast<std::int64_t>(cutting ? (lo + hi) / 2 : hi + 1);
    splits.push_back(axis_plane(axis, std::min(pos, kCoordLimit)));
  }
  Polygon neg, pos;
  std::size_t i = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(clip(tris[i], splits[i], neg, pos));
    i = (i + 1) & (kCount - 1);
  }
}
void BM_ClipTriangleAxisCut(benchmark::State& state) { clip_bench(state, true); }
void BM_ClipTriangleAxisNoCut(benchmark::State& state) { clip_bench(state, false); }
BENCHMARK(BM_ClipTriangleAxisCut);
BENCHMARK(BM_ClipTriangleAxisNoCut);

}  // namespace
