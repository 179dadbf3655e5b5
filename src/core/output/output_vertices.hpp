#pragma once
// The mesh stage's shared data: the distinct exact output points, flat
// polygon cycles over them, and what the input stage knows of the triangles.
#include <array>
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include <atomic>

#include "core/model/output_polygon.hpp"
#include "core/model/input_topology.hpp"
#include "core/support/fill_vector.hpp"
#include "ember/mesh.hpp"
#include "geometry/exact_order.hpp"

namespace ember::core {

/// Lowers `slot` to `value` if that is smaller, safely against concurrent
/// callers (relaxed: only the final minimum is read, after the parallel loop).
/// The mesh stage's "first use" numbers are such minima.
template <typename T>
void atomic_min(T& slot, T value) {
  std::atomic_ref<T> ref(slot);
  for (T seen = ref.load(std::memory_order_relaxed);
       value < seen && !ref.compare_exchange_weak(seen, value, std::memory_order_relaxed);) {
  }
}

/// Flat cyclic vertex lists: polygon p is ids[offsets[p] .. offsets[p+1]).
struct Cycles {
  std::vector<std::uint32_t> offsets{0};
  std::vector<std::uint32_t> ids;
  std::size_t size() const { return offsets.size() - 1; }
  std::span<const std::uint32_t> operator[](std::size_t p) const {
    return {ids.data() + offsets[p], offsets[p + 1] - offsets[p]};
  }
};

/// Distinct exact points of the output.
struct OutputVertices {
  /// A representative of each distinct point (FillVector: the weld writes
  /// every entry in parallel; zeroing ~100 bytes per point first was serial).
  FillVector<Point> exact;
  std::vector<Vec3d> rounded;  ///< its correctly rounded position in caller units
  Cycles corners;              ///< per output polygon: its corners' ids, in the polygon's own order
};

}  // namespace ember::core
