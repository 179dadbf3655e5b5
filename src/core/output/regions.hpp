#pragma once
// Step 3 of the mesh stage (mesh_output.hpp): pieces of one oriented plane merged into regions.
#include <array>
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "core/output/output_vertices.hpp"

namespace ember::core {

/// A region: pieces of one oriented plane joined across shared edges (its
/// pieces are listed in Regions::piece_ids).
struct Region {
  Plane plane;               ///< the oriented support plane (outward normal)
  std::uint32_t source = 0;  ///< lowest source id among its pieces (provenance)
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
  std::vector<BoundaryEdge> edges;        ///< grouped by region, loops linked by `next`
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
/// Polygons flagged in `skip` (step 2b's) are left out. With `source_groups`
/// (the face group of each source id, core/input/face_groups.hpp), pieces of
/// different groups never share a region.
Regions build_regions(std::span<const OutputPolygon> polys, const Cycles& cycles, const OutputVertices& verts,
                      const std::vector<char>& skip, std::span<const std::uint32_t> source_groups = {});

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

}  // namespace ember::core
