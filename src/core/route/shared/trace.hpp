#pragma once
// Winding-number tracing along axis-parallel segments between dyadic points
// (paper Sections 3.4, 4.2.2 and 4.4). A trace either adds the exact signed
// crossings of every polygon to a winding-number vector, or reports that the
// segment meets some polygon degenerately (at an edge or vertex, at a segment
// end, or touching it in its plane): then the caller chooses another path.
// There are no tolerances: every decision is an exact predicate.
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <atomic>
#include <span>
#include <vector>

#include "core/model/soup.hpp"

namespace ember::core {

/// Does the part of line (l0, l1) where every constraint classifies <= 0 have a
/// point? Each constraint not parallel to the line bounds it on one side; at
/// least one must be transverse.
bool line_region_nonempty(const Plane& l0, const Plane& l1, std::span<const Plane> constraints);
/// Same, but the region must have positive length (not a single point).
bool line_region_has_length(const Plane& l0, const Plane& l1, std::span<const Plane> constraints);

/// An axis-parallel segment: the line (l0, l1) = `line` (along `axis`, moving
/// in direction `dir` = +-1) between the bounds r0 <= 0 and r1 <= 0.
struct AxisSegment {
  AxisLine line;
  Plane l0, l1, r0, r1;
  int dir = 1;
  std::array<double, 3> lo{}, hi{};  ///< conservative bounding box
  std::array<double, 2> uv{};        ///< line_point_approx(line), for the miss filter
};

/// The segment from dyadic a to dyadic b (same shift), which differ only in
/// coordinate `axis`; false (seg untouched) if a = b.
bool make_axis_segment(const Dyadic& a, const Dyadic& b, int axis, AxisSegment& seg);

/// Adds polygon p's crossing of the segment to w. False when the segment
/// meets p degenerately: at an edge or vertex, at a segment end, or touching
/// it within p's plane. Exact on its own; callers first skip the polygons
/// that miss the segment's box or clearly miss its line (line_clearly_misses),
/// the cheap filters, which is where most polygons leave.
bool add_crossing(const AxisSegment& s, const SoupPolygon& p, Wnv& w);
/// The same for a built polygon of `operand` (built_polygon).
bool add_crossing(const AxisSegment& s, const Polygon& poly, std::uint32_t operand, Wnv& w);

/// Calls visit(i, w, delta, scratch) for every polygon i < n of a trace's
/// soup, with a Polygon scratch for building unbuilt triangles; false as soon
/// as one call is (then w and delta are unspecified). visit only adds
/// integers to w and delta (crossings), so the sums do not depend on the
/// order: a root soup, where the proof classifies one polygon per component
/// against the whole input (on a large input a long pass that would be
/// serial at any thread count), is scanned in parallel chunks with their own
/// sums.
template <typename Visit>
bool scan_soup(std::size_t n, Wnv& w, Wnv& delta, Visit&& visit) {
  constexpr std::size_t kParallel = std::size_t{1} << 16, kChunk = std::size_t{1} << 13;
  if (n < kParallel) {
    Polygon scratch;
    for (std::size_t i = 0; i < n; ++i)
      if (!visit(i, w, delta, scratch)) return false;
    return true;
  }
  const std::size_t chunks = (n + kChunk - 1) / kChunk;
  std::vector<Wnv> sums(chunks), deltas(chunks);
  std::atomic<bool> met_degenerately{false};
  const auto scan_chunk = [&](std::size_t c) {
    if (met_degenerately.load(std::memory_order_relaxed)) return;
    Wnv& cw = sums[c];
    Wnv& cd = deltas[c];
    cw.assign(w.size(), 0);
    cd.assign(delta.size(), 0);
    Polygon scratch;
    for (std::size_t i = c * kChunk, end = std::min(n, i + kChunk); i < end; ++i)
      if (!visit(i, cw, cd, scratch)) {
        met_degenerately = true;
        return;
      }
  };
  // Isolated: the caller (a proof's task, a split) waits for its own chunks,
  // not for whatever unrelated task its thread would take meanwhile.
  tbb::this_task_arena::isolate([&] { tbb::parallel_for(std::size_t{0}, chunks, scan_chunk); });
  if (met_degenerately) return false;
  for (std::size_t c = 0; c < chunks; ++c) {
    for (std::size_t o = 0; o < w.size(); ++o) w[o] += sums[c][o];
    for (std::size_t o = 0; o < delta.size(); ++o) delta[o] += deltas[c][o];
  }
  return true;
}

/// Polygons of this operand are ignored by a trace (its winding number is
/// known otherwise); kNoSkip counts every polygon.
inline constexpr std::uint32_t kNoSkip = 0xffffffffu;

/// Adds to w the winding-number change from a to b, two dyadic points with the
/// same shift that differ only in coordinate `axis`. Returns false when the
/// segment meets a polygon degenerately; w is then unspecified. w[skip] is
/// not maintained.
/// `flat`, if given, approximates `soup` (same polygons, same order): the
/// miss filter then reads it instead of the polygons (same answers, faster).
bool trace_axis_segment(const Soup& soup, const Dyadic& a, const Dyadic& b, int axis, Wnv& w,
                        std::uint32_t skip = kNoSkip, const SoupApprox* flat = nullptr);

/// Axis-parallel path a -> b changing coordinates in the given order (each
/// segment moves one coordinate). Same contract as trace_axis_segment.
bool trace_path(const Soup& soup, const Dyadic& a, const Dyadic& b, const std::array<int, 3>& order, Wnv& w,
                std::uint32_t skip = kNoSkip, const SoupApprox* flat = nullptr);

}  // namespace ember::core
