#pragma once
// A subproblem of the subdivision: a box, its polygons, and a reference point with known winding numbers.
#include <cstdint>
#include <memory>

#include "core/model/soup.hpp"

namespace ember::core {

/// The splits that made a subproblem's box, as a chain from the subproblem
/// up to the root (null: the root's box). Shared by a subproblem's children,
/// immutable, so that an output piece can name its box by its chunk's path.
struct SplitStep {
  std::shared_ptr<const SplitStep> parent;
  std::int64_t position = 0;
  int axis = 0;
  bool upper = false;  ///< the subproblem lies above the split plane
};
using SplitPath = std::shared_ptr<const SplitStep>;

/// A self-contained subproblem: polygons clipped to a closed integer box and a
/// reference point strictly inside the box with its winding-number vector.
struct Subproblem {
  Box box;
  SplitPath path;  ///< the splits that made `box` (null at the root)
  Soup soup;
  Dyadic ref;
  Wnv ref_w;
};

}  // namespace ember::core
