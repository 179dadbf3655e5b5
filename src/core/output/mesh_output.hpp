#pragma once
// The mesh stage: turns the core's exact output polygons (a soup of convex
// pieces with T-junctions) into an indexed triangle mesh that is closed
// wherever the exact result is closed.
//
//  1. exact_weld:   one id per exact point (equal points, however represented,
//                   share it); each id is rounded to double once.
//  2. tjunctions:   every vertex lying in the open interior of a polygon edge
//                   is inserted into that edge (exact incidence tests).
//  2b. pass_through: whole input triangles that gained no vertex and share no
//                   edge with a piece of their oriented plane go straight to
//                   the output (steps 3-4 would give them back unchanged).
//  3. regions:      pieces in the same oriented plane that share an edge are
//                   merged (their common edges cancel); a boundary vertex that
//                   only joins collinear edges between the same two regions is
//                   removed on both sides.
//  4. triangulate:  every region (outer loop + holes) is ear-clipped with exact
//                   orientation tests in its plane's projection.
// Everything is decided on exact points; no epsilon anywhere.
#include <array>
#include <atomic>
#include <cstdint>
#include <functional>
#include <span>
#include <vector>

#include "core/support/fill_vector.hpp"
#include "core/route/general/solve.hpp"
#include "ember/boolean.hpp"
#include "core/input/quantize.hpp"
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
  std::vector<Vec3d> rounded;   ///< its correctly rounded position in caller units
  Cycles corners;               ///< per output polygon: its corners' ids, in the polygon's own order
};

/// What the set-up and the proof know about the input triangles (by id).
/// Their welded grid vertex ids, made global: corner k of triangle t of
/// operand o is vertex operand_base[o] + by_triangle[t][k]. Equal ids are
/// equal points; equal points of different operands have different ids.
struct InputTopology {
  std::span<const std::array<std::uint32_t, 3>> by_triangle;
  std::vector<std::uint32_t> operand_base;  ///< one per operand, then the total
  /// Bit k of triangle t: its edge k is a manifold edge of its operand
  /// (EdgeMatching::manifold). Empty: unknown.
  std::span<const std::uint8_t> manifold_edges;
  /// Per operand: solid (proven or promised; no two of its triangles meet
  /// beyond a shared vertex or edge). Empty: unknown.
  std::vector<char> solid;
};

/// Step 1. Polygons keep their stored (unflipped) vertex order. With `ids`,
/// the corners of unbuilt triangles are welded through their input vertex
/// ids (faster; the same result).
OutputVertices exact_weld(std::span<const OutputPolygon> polys, const Quantizer& q,
                          const InputTopology* ids = nullptr);

class VertexIndex;  // core/mesh/vertex_index.hpp

/// Every output vertex, bucketed for searches along segments. With two
/// operands of which one is solid and `topology`'s manifold edges, each
/// cell is ordered by which operands' polygons use the vertex, so that step
/// 2 can search an edge between two whole triangles of a solid operand for
/// the other operand's vertices alone (tjunctions.cpp, whole_solid_edge):
/// far from the other operand those parts of the cells are empty.
VertexIndex index_output_vertices(std::span<const OutputPolygon> polys, const OutputVertices& verts,
                                  const InputTopology* topology = nullptr);

/// The corner edges (corner c runs from corners.ids[c] to the next corner of
/// its polygon) grouped by undirected id pair: every edge of a pair is the
/// same segment, so it is searched once.
struct EdgePairs {
  static constexpr std::uint32_t kNoRun = UINT32_MAX;
  std::vector<std::uint32_t> corner;     ///< corners sorted by (pair, corner)
  std::vector<std::uint32_t> run_begin;  ///< pair r owns corner[run_begin[r] .. run_begin[r+1])
  std::vector<std::uint32_t> run_of;     ///< per corner: its pair (kNoRun: a settled polygon's)
  std::vector<std::uint32_t> poly_of;    ///< per corner: its polygon
};
/// With `polys`, the corners of settled polygons (OutputPolygon::settled)
/// are left out: their edges need no search and join nothing.
EdgePairs group_edges_by_pair(const Cycles& corners, std::span<const OutputPolygon> polys = {});

/// Step 2. Per polygon (unflipped order): corners with every vertex that lies
/// in the open interior of an edge inserted in order along it. Counts the
/// insertions in `inserted`. `pairs` groups verts.corners. `index` must have
/// been built with the same `topology`.
Cycles insert_tjunction_vertices(std::span<const OutputPolygon> polys, const OutputVertices& verts,
                                 const VertexIndex& index, const EdgePairs& pairs, std::size_t& inserted,
                                 const InputTopology* topology = nullptr);

/// Step 2b. Per polygon, 1 if it leaves the mesh stage as it came: a settled
/// polygon, or an unbuilt triangle (a whole input triangle) that gained no
/// vertex in step 2 and shares no edge with a piece of the same oriented
/// plane, so that step 3 would make it a region of its own and step 4 would
/// emit it unchanged.
/// Such triangles skip steps 3 and 4. `cycles` are step 2's.
std::vector<char> pass_through_triangles(std::span<const OutputPolygon> polys, const OutputVertices& verts,
                                         const EdgePairs& pairs, const Cycles& cycles);

/// A region: pieces of one oriented plane joined across shared edges (its
/// pieces are listed in Regions::piece_ids).
struct Region {
  Plane plane;                   ///< the oriented support plane (outward normal)
  std::uint32_t source = 0;      ///< lowest source id among its pieces (provenance)
};

/// A directed boundary edge of a region (the region lies to its left, seen
/// from the region's outward normal).
struct BoundaryEdge {
  std::uint32_t from = 0, to = 0;
  std::uint32_t region = 0;
  std::uint32_t next = 0;  ///< next boundary edge of the same loop
  bool alive = true;
};

struct Regions {
  std::vector<Region> regions;
  std::vector<BoundaryEdge> edges;  ///< grouped by region, loops linked by `next`
  std::vector<std::uint32_t> edge_begin;  ///< region r owns edges[edge_begin[r] .. edge_begin[r+1])
  /// Output polygon indices by region (flat, so that the many one-piece
  /// regions of a curved result cost no allocation each): region r's pieces
  /// are piece_ids[piece_begin[r] .. piece_begin[r+1]).
  std::vector<std::uint32_t> piece_ids, piece_begin;
  std::span<const std::uint32_t> pieces(std::uint32_t r) const {
    return {piece_ids.data() + piece_begin[r], piece_begin[r + 1] - piece_begin[r]};
  }
};

/// A piece's cycle (step 2's, unflipped order) around its outward normal,
/// repeated ids dropped, into `loop`.
void piece_loop(const OutputPolygon& poly, std::span<const std::uint32_t> ids, std::vector<std::uint32_t>& loop);

/// Step 3 (merge). `cycles` are the polygons after step 2, unflipped.
/// Polygons flagged in `skip` (step 2b's) are left out.
Regions build_regions(std::span<const OutputPolygon> polys, const Cycles& cycles, const OutputVertices& verts,
                      const std::vector<char>& skip);

/// One removal of step 3b: vertex v spliced out of edges in_1 (region 1) and
/// in_2 (region 2), killing out_1 and out_2.
struct Removal {
  std::uint32_t v, in_1, out_1, in_2, out_2;
};

/// Step 3 (collinear vertices). Returns the removals in the order made.
/// Vertices flagged in `pinned` (corners of step 2b's triangles, whose
/// edges the regions do not see) are kept.
std::vector<Removal> remove_collinear_vertices(Regions& regions, std::size_t vertex_count,
                                               const std::vector<char>& pinned);

/// Puts back every removal that touches a region in `failed` (and every later
/// removal that touched the same edges), newest first, so that regions
/// triangulated piece by piece keep matching their neighbours. Returns the
/// regions outside `failed` whose boundary changed.
/// `undone` (one flag per removal) carries what earlier calls put back.
std::vector<std::uint32_t> restore_vertices(Regions& regions, const std::vector<Removal>& removals,
                                            const std::vector<char>& failed, std::vector<char>& undone);

/// Orientation of a, b, c seen from the positive side of `plane` (+1 counter-clockwise).
int orient_in_plane(const Point& a, const Point& b, const Point& c, const Plane& plane);

/// orient_in_plane with the plane's projection (its dominant axis, and which
/// way it faces) worked out once, for loops that orient many triples in one
/// plane (ear clipping: tens of thousands per curved result).
class PlaneOrientation {
 public:
  explicit PlaneOrientation(const Plane& plane);
  int operator()(const Point& a, const Point& b, const Point& c) const {
    const int o = orient2d_uv(a, b, c, u_, v_);
    return flip_ ? -o : o;
  }

 private:
  int u_ = 1, v_ = 2;
  bool flip_ = false;
};

/// Step 4 for one region: appends triangles (counter-clockwise around the
/// region's outward normal). False if the region's loops are not a polygon
/// with holes that ear clipping can handle; nothing is appended then.
bool triangulate_region(const Regions& regions, std::uint32_t region, const OutputVertices& verts,
                        std::vector<std::array<std::uint32_t, 3>>& out);

/// Loops longer than this find the vertices an ear must not hold through a
/// grid (loop_grid.hpp) instead of walking round the loop for each ear.
inline constexpr std::size_t kEarGridLoop = 64;

/// Ear-clips one cyclic polygon (no holes) given as vertex ids, counter-
/// clockwise around `plane`. False if no valid ear can be found.
/// `grid_from`: the loop length from which the grid is used (tests compare
/// both ways; the triangles are the same).
bool triangulate_loop(std::span<const std::uint32_t> loop, const Plane& plane, const OutputVertices& verts,
                      std::vector<std::array<std::uint32_t, 3>>& out, std::size_t grid_from = kEarGridLoop + 1);

/// Ear-clips a polygon with holes: `outer` counter-clockwise around `plane`,
/// each hole clockwise, joined to it by bridges first. False if a bridge or
/// an ear cannot be found.
bool triangulate_with_holes(std::vector<std::uint32_t> outer, std::vector<std::vector<std::uint32_t>> holes,
                            const Plane& plane, const OutputVertices& verts,
                            std::vector<std::array<std::uint32_t, 3>>& out);

/// +1 if the loop runs counter-clockwise around `plane`, -1 clockwise, 0 if
/// its turn at its lexicographically smallest vertex is straight.
int loop_orientation_in_plane(const std::vector<std::uint32_t>& loop, const Plane& plane, const OutputVertices& verts);

/// Whether vertex x (on `plane`) lies inside the loop (1), outside (0) or
/// on it (-1), exactly: a ray's crossings in the projection along the
/// plane's dominant axis.
int locate_in_loop(const std::vector<std::uint32_t>& loop, std::uint32_t x, const Plane& plane,
                   const OutputVertices& verts);

/// Step 5b for one region's triangles (a triangulation of a plane region):
/// every vertex that some output triangle uses (`used`, per vertex id) and
/// that lies strictly inside a diagonal (an edge two of the triangles share)
/// is inserted, splitting both triangles. Such a vertex is a point where
/// another part of the result touches the region's interior. (Vertices no
/// triangle uses, such as the inner corners of merged pieces, are skipped.)
/// Returns the number of vertices inserted (0: `tris` unchanged).
std::size_t split_diagonals(const Plane& plane, const OutputVertices& verts, const VertexIndex& index,
                            const std::vector<char>& used, std::vector<std::array<std::uint32_t, 3>>& tris);

/// Twice the area vector of a face of rounded (double) vertices, summed from
/// differences to its first vertex in extended precision, is exactly zero.
/// Shared by the mesh stage (rounded_degenerate) and the polygon export (slivers).
bool rounded_area_is_zero(const std::vector<Vec3d>& pos, std::span<const std::uint32_t> face);

/// The indexed mesh of `tris` (vertex ids below vertex_count): vertices
/// numbered by first use (as a serial pass along the triangles would, in
/// parallel), each placed at position(id); the triangles from `whole_count`
/// on (the first ones are whole input triangles, whose rounded area is
/// known) are counted in `rounded_degenerate` when their rounded corners
/// have zero area. Shared by the mesh stage and the direct route
/// (direct_mesh.hpp).
void write_indexed_mesh(std::span<const std::array<std::uint32_t, 3>> tris, std::size_t vertex_count,
                        const std::function<Vec3d(std::uint32_t)>& position, std::size_t whole_count, Mesh& mesh,
                        std::size_t& rounded_degenerate);

struct MeshOutputStats {
  std::size_t tjunctions = 0;          ///< vertices inserted into edges
  std::size_t collinear_removed = 0;   ///< boundary vertices removed on both sides
  std::size_t regions = 0;
  std::size_t fallback_regions = 0;    ///< regions triangulated piece by piece
  std::size_t rounded_degenerate = 0;  ///< triangles whose rounded corners have zero area
  double weld_ms = 0, tjunction_ms = 0, regions_ms = 0, triangulate_ms = 0;  ///< time per step
};

struct MeshOutput {
  Mesh mesh;
  std::vector<Provenance> provenance;
  MeshOutputStats stats;
};

/// Steps 1-4. `sources[id]` is the provenance of source polygon id; `ids`
/// (optional) speeds up step 1.
MeshOutput build_triangle_mesh(std::span<const OutputPolygon> polys, const Quantizer& q,
                               std::span<const Provenance> sources, const InputTopology* ids = nullptr);

}  // namespace ember::core
