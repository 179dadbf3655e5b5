// Connected components of grid triangles across manifold edges (components.hpp).
#include "core/model/components.hpp"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <atomic>

namespace ember::core {

namespace {

// A concurrent union-find over triangle ids. Every parent pointer points to
// a smaller or equal id, so a root is the smallest id of its tree and the
// final roots are each component's smallest id, whatever the schedule: the
// same answer as a serial pass, computed in parallel (the proof and the
// solid path both run it over every triangle, so a serial pass would cap
// their scaling). Links are compare-and-swaps on roots;
// path halving stores an ancestor (a smaller id of the same set), which is
// correct whenever it lands.
using Parents = FillVector<std::uint32_t>;

std::uint32_t load(Parents& parent, std::uint32_t x) {
  return std::atomic_ref<std::uint32_t>(parent[x]).load(std::memory_order_relaxed);
}

/// Root of x, halving the path on the way.
std::uint32_t find(Parents& parent, std::uint32_t x) {
  for (std::uint32_t p = load(parent, x); p != x; p = load(parent, x)) {
    const std::uint32_t g = load(parent, p);
    if (g != p) std::atomic_ref<std::uint32_t>(parent[x]).store(g, std::memory_order_relaxed);
    x = p;
  }
  return x;
}

/// Joins the sets of a and b: the larger root is linked below the smaller.
void unite(Parents& parent, std::uint32_t a, std::uint32_t b) {
  for (;;) {
    std::uint32_t ra = find(parent, a), rb = find(parent, b);
    if (ra == rb) return;
    if (ra < rb) std::swap(ra, rb);
    // ra is the larger root; it may have been linked meanwhile: then retry.
    std::uint32_t expected = ra;
    if (std::atomic_ref<std::uint32_t>(parent[ra]).compare_exchange_strong(expected, rb, std::memory_order_relaxed))
      return;
  }
}

/// Calls f(i, j) for each kept local triangle i in [begin, end) and each
/// kept neighbour j > i in [0, count): triangle first + i of the grid, its
/// neighbours mutual (both ends of a manifold edge), so every pair once.
template <typename Keep, typename F>
void each_kept_pair(const GridTriangles& grid, std::uint32_t first, std::size_t count, const Keep& keep,
                    std::size_t begin, std::size_t end, F&& f) {
  for (std::size_t i = begin; i != end; ++i) {
    if (!keep(first + i)) continue;
    for (const std::uint32_t n : grid.neighbors[first + i]) {
      const std::uint32_t j = n - first;  // wraps past count for ids below first and kNoNeighbor
      if (j < count && j > i && keep(n)) f(static_cast<std::uint32_t>(i), j);
    }
  }
}

/// The serial pass, for one thread: a flood fill from each kept triangle
/// not yet reached, in ascending order, so each component's first triangle
/// is its smallest id (the union-find's answer; the fill costs about half its
/// instructions, and the concurrent union-find 1.5x its own).
template <typename Keep>
Parents serial_components(const GridTriangles& grid, std::uint32_t first, std::size_t count, const Keep& keep) {
  constexpr std::uint32_t kUnreached = UINT32_MAX;
  Parents root(count, kUnreached);
  std::vector<std::uint32_t> stack;
  for (std::size_t s = 0; s < count; ++s) {
    if (root[s] != kUnreached || !keep(first + s)) continue;
    root[s] = static_cast<std::uint32_t>(s);
    stack.push_back(static_cast<std::uint32_t>(s));
    while (!stack.empty()) {
      const std::uint32_t t = stack.back();
      stack.pop_back();
      for (const std::uint32_t n : grid.neighbors[first + t]) {
        const std::uint32_t j = n - first;  // wraps past count for ids below first and kNoNeighbor
        if (j < count && root[j] == kUnreached && keep(n)) {
          root[j] = static_cast<std::uint32_t>(s);
          stack.push_back(j);
        }
      }
    }
  }
  return root;
}

/// Components of the kept triangles first .. first + count - 1, joined
/// across manifold edges inside that range: per kept triangle first + i,
/// entry i is the smallest id of its component.
template <typename Keep>
FillVector<std::uint32_t> components(const GridTriangles& grid, std::uint32_t first, std::size_t count,
                                     const Keep& keep) {
  Parents parent;
  if (tbb::this_task_arena::max_concurrency() == 1) {
    parent = serial_components(grid, first, count, keep);
  } else {
    parent.resize(count);  // every entry written below (a value-initializing resize was a serial pass)
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, count, 4096), [&](const tbb::blocked_range<std::size_t>& r) {
      for (std::size_t i = r.begin(); i != r.end(); ++i) parent[i] = static_cast<std::uint32_t>(i);
    });
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, count, 1024), [&](const tbb::blocked_range<std::size_t>& r) {
      each_kept_pair(grid, first, count, keep, r.begin(), r.end(),
                     [&](std::uint32_t i, std::uint32_t j) { unite(parent, i, j); });
    });
    // Every root is final now: point each kept entry at it (find only reads
    // and halves paths, which stays correct under the concurrent halving).
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, count, 4096), [&](const tbb::blocked_range<std::size_t>& r) {
      for (std::size_t i = r.begin(); i != r.end(); ++i) {
        if (!keep(first + i)) continue;
        const std::uint32_t root = find(parent, static_cast<std::uint32_t>(i));
        std::atomic_ref<std::uint32_t>(parent[i]).store(root, std::memory_order_relaxed);
      }
    });
  }
  if (first != 0)
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, count, 16384), [&](const tbb::blocked_range<std::size_t>& r) {
      for (std::size_t i = r.begin(); i != r.end(); ++i) parent[i] += first;
    });
  return parent;
}

}  // namespace

FillVector<std::uint32_t> neighbour_components(const GridTriangles& grid, std::span<const char> keep) {
  return components(grid, 0, keep.size(), [&](std::size_t i) { return keep[i] != 0; });
}

FillVector<std::uint32_t> neighbour_components(const GridTriangles& grid, std::uint32_t first, std::size_t count) {
  return components(grid, first, count, [](std::size_t) { return true; });
}

}  // namespace ember::core
