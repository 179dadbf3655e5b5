#pragma once
// The public entry point: exact n-ary mesh Booleans (EMBER, Trettner et al. 2022).
//
//   ember::Mesh a = ..., b = ...;
//   ember::BooleanResult r = ember::boolean({a, b}, ember::Operation::Union);
//   // r.mesh: an indexed triangle mesh, outward oriented, closed when the
//   // exact result is (BooleanOptions::output selects raw polygons instead)
//
// All operands are quantized together onto one integer grid (|x| <= 2^25, a
// power-of-two scale so integer and dyadic inputs stay exact); the Boolean is
// then exact, and results are mapped back to the caller's units with one
// rounding per coordinate.
#include <cstddef>
#include <cstdint>
#include <functional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "ember/mesh.hpp"

namespace ember {

enum class Operation {
  Union,         ///< inside any operand
  Intersection,  ///< inside every operand
  Difference,    ///< inside the first operand and outside all others
  Xor,           ///< inside an odd number of operands
  AtLeastK,      ///< inside at least BooleanOptions::min_k operands
};

/// A winding-number vector: one winding number per operand.
using WindingVector = std::span<const int>;
/// Maps a winding-number vector to inside (true) / outside (false).
using Indicator = std::function<bool(WindingVector)>;
/// Progress of one boolean() call: the phase now starting ("prepare",
/// "solid check", "solve", "export", "done") and a rough estimate of the
/// fraction of the whole run done so far (0..1, non-decreasing, 1 with "done").
using ProgressCallback = std::function<void(std::string_view phase, double fraction)>;

struct BooleanOptions {
  /// Worker threads; 0 uses all hardware threads. Results do not depend on it.
  int threads = 0;
  /// For Operation::AtLeastK.
  int min_k = 1;
  /// Operands that are not closed (some edge is not matched by an opposite edge)
  /// are an error unless this is set; then they are used as given and a warning
  /// is added to the result.
  bool allow_open = false;
  /// When set, replaces the operation's indicator function. (Custom
  /// indicators disable the early termination that built-in operations get.)
  Indicator indicator;
  /// Per operand (or empty): the caller guarantees the operand is *solid*:
  /// closed, outward-oriented, free of self-intersections, and without nested
  /// or touching components, so its winding number is 0 or 1 everywhere.
  /// ember's own results are solid. This enables the paper's shortcuts
  /// (Fig. 11) and makes Booleans much faster; a wrong claim gives a wrong
  /// result, so leave it unset for meshes of unknown quality.
  std::vector<bool> solid;
  /// Shorthand: every operand is solid (as above).
  bool all_solid = false;
  /// Prove the operands not promised solid solid (or not) before the Boolean,
  /// exactly: closed, no two triangles meeting except in shared vertices or
  /// edges, winding number 0 in front of every face. Proven operands get the
  /// same shortcuts as promised ones; the others take the general path. Any
  /// doubt (touching parts, T-junctions, non-manifold edges, more than a few
  /// components on large inputs) counts as "not solid", never as solid.
  /// Costs a fraction of the Boolean it speeds up; turn off only for inputs
  /// known to fail it.
  bool detect_solid = true;
  /// Which routes may solve it. Automatic (default): the fastest exact one
  /// whose preconditions hold; with every operand solid that is the solid
  /// path, which needs no kd subdivision (docs/design.md, "Solid path").
  /// General: always the paper's subdivision, which is exact for any input
  /// and gives the same surface; for checking one route against the other.
  enum class Route { Automatic, General } route = Route::Automatic;
  /// Output form. Triangles (default): an indexed triangle mesh, watertight
  /// wherever the exact result is closed (exact points welded, T-junctions
  /// resolved, coplanar pieces merged and re-triangulated exactly).
  /// Polygons: the core's raw convex pieces, as the paper emits them
  /// (T-junctions, one polygon per BSP piece).
  enum class Output { Triangles, Polygons } output = Output::Triangles;
  /// Called at phase boundaries so callers can show progress on long runs
  /// (the library itself never prints). Always called from the thread that
  /// called boolean(), one call at a time, so it needs no locking of its own;
  /// it should return quickly. An exception it throws propagates out of
  /// boolean(). Empty: no calls.
  ProgressCallback progress;
};

/// What the solid check (BooleanOptions::detect_solid) found for one operand.
enum class SolidStatus {
  NotChecked,        ///< detect_solid off, or no triangles left on the grid
  Promised,          ///< BooleanOptions::solid / all_solid: taken on trust
  Proven,            ///< proven solid: takes the fast path
  Open,              ///< not closed (OperandReport::open_edges): never solid
  SelfIntersecting,  ///< triangles meet beyond shared vertices/edges (OperandReport::self_intersecting_pairs)
  Misoriented,       ///< components inverted or nested (OperandReport::misoriented_components)
  Undecided,         ///< beyond the proof's work budget or no trace path: treated as not solid
};

/// Per operand: what quantization did to it and what the solid check found.
struct OperandReport {
  std::size_t triangles = 0;            ///< after fan triangulation of its faces
  std::size_t collapsed_triangles = 0;  ///< had area in the input, degenerate on the grid (dropped)
  std::size_t flipped_triangles = 0;    ///< the grid reversed their orientation
  SolidStatus solid = SolidStatus::NotChecked;
  std::size_t open_edges = 0;               ///< edges not matched by an opposite edge
  std::size_t self_intersecting_pairs = 0;  ///< pairs found (see self_intersecting_pairs_complete)
  /// False when self_intersecting_pairs is only a lower bound: the search
  /// stopped at kMaxReportedPairs or, in a pile of overlapping slivers, at its
  /// work budget once a pair had decided the verdict.
  bool self_intersecting_pairs_complete = true;
  std::size_t misoriented_components = 0;  ///< components with winding number != 0 in front
  static constexpr std::size_t kMaxReportedPairs = 1000;
};

/// One figure of BooleanStats::diagnostics.
struct Diagnostic {
  std::string name;  ///< e.g. "solve_ms", "direct_mesh"
  double value = 0;  ///< a count, a flag (0 or 1) or milliseconds, as the name says
};

struct BooleanStats {
  std::size_t input_triangles = 0;
  std::size_t dropped_degenerate = 0;   ///< triangles degenerate on the integer grid (collapsed or already degenerate)
  std::size_t collapsed_triangles = 0;  ///< of those, triangles with area in the input (sum over operands)
  std::size_t flipped_triangles = 0;    ///< triangles whose orientation the grid reversed (sum over operands)
  double grid_step = 0;                 ///< quantization grid spacing in the caller's units
  std::size_t output_polygons = 0;
  std::size_t dropped_slivers = 0;  ///< exact output slivers whose rounded vertices have zero area
  std::size_t solid_operands = 0;   ///< operands treated as solid (promised or proven)
  std::size_t output_vertices = 0;
  /// Output triangles whose rounded (double) corners have zero area.
  std::size_t rounded_degenerate = 0;
  std::vector<OperandReport> operands;  ///< one per operand
  double time_ms = 0;                   ///< quantization + core + export (no file I/O)
  int threads = 1;                      ///< worker threads used
  /// How the run went inside, for profiling and reports: the route taken,
  /// what the mesh stage did, the time of each phase. Names and meanings:
  /// docs/cli.md, "Statistics" (the CLI's --stats prints them all). A
  /// figure may be added or removed between minor versions; look them up by
  /// name (diagnostic()).
  std::vector<Diagnostic> diagnostics;
  /// The value of the diagnostic called `name`; 0 when the run did not record it.
  double diagnostic(std::string_view name) const {
    for (const Diagnostic& d : diagnostics)
      if (d.name == name) return d.value;
    return 0;
  }
};

struct BooleanResult {
  Mesh mesh;                           ///< triangles (default) or convex polygons (Output::Polygons)
  std::vector<Provenance> provenance;  ///< one per face of mesh
  BooleanStats stats;
  std::vector<std::string> warnings;
};

/// Computes the Boolean of any number of operands in one pass. Throws
/// ember::Error for invalid input (non-finite coordinates, bad indices, open
/// operands without allow_open, no operands, min_k out of range).
BooleanResult boolean(std::span<const Mesh> operands, Operation op, const BooleanOptions& options = {});

inline BooleanResult boolean(std::initializer_list<Mesh> operands, Operation op, const BooleanOptions& options = {}) {
  return boolean(std::span<const Mesh>(operands.begin(), operands.size()), op, options);
}

/// Every layer at once (the paper's Fig. 21): element k-1 is the solid
/// inside at least k operands (what boolean(operands, AtLeastK) gives with
/// min_k = k), for k = 1 .. operands.size(), all from ONE computation of the
/// winding-number vectors; each layer is built as its own watertight mesh.
/// The layers share the stats of the solve (time_ms is the whole call's);
/// each has its own output counts. At most 255 operands;
/// options.indicator and min_k must be left unset. The direct route does not
/// run (it makes one mesh), and the general path has no early terminations
/// here (every change of the count is output).
std::vector<BooleanResult> boolean_layers(std::span<const Mesh> operands, const BooleanOptions& options = {});

/// The solid check's finding in words: "proven solid", "not solid: self-intersecting
/// (3 triangle pairs meet ...)", ... (for warnings and reports).
std::string describe_solid_check(const OperandReport& report);

/// Whether report.self_intersecting_pairs is only a lower bound: the search
/// stopped counting (self_intersecting_pairs_complete false) or the count
/// reached kMaxReportedPairs. describe_solid_check then says "at least".
bool self_intersection_count_is_lower_bound(const OperandReport& report);

/// The indicator function of an operation over n operands.
Indicator indicator_for(Operation op, std::size_t operands, int min_k = 1);

}  // namespace ember
