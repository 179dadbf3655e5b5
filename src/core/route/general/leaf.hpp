#pragma once
// Leaf computation (paper Sections 4.3 and 4.4): polygon-local BSPs and
// classification of every piece by a segment trace to the reference point.
#include <vector>

#include "core/model/output_polygon.hpp"
#include "core/model/solve_context.hpp"
#include "core/route/general/subproblem.hpp"

namespace ember::core {

/// Winding-number vectors just in front of and behind polygon t of pb's soup
/// (the whole polygon, which must not be crossed or overlapped by any other
/// polygon of the soup), traced from pb's reference point. False if no valid
/// path was found.
bool classify_polygon(const Subproblem& problem, const SoupPolygon& t, Wnv& w_front, Wnv& w_back);

/// Leaf computation (exposed for tests). Path pieces carry path 0.
void solve_leaf(const Subproblem& problem, const SolveContext& ctx, std::vector<OutputPolygon>& out);

}  // namespace ember::core
