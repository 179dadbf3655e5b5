#pragma once
// The plain mesh type that crosses the library boundary: double positions and
// polygon faces (triangles or n-gons) in one flat index buffer.
#include <cstddef>
#include <cstdint>
#include <initializer_list>
#include <span>
#include <string>
#include <vector>

namespace ember {

/// Where an output face of a Boolean came from (ember::boolean's result;
/// PLY output can carry it as face properties).
struct Provenance {
  std::uint32_t operand;  ///< index into the operands
  std::uint32_t face;     ///< face index within that operand
  friend bool operator==(const Provenance&, const Provenance&) = default;
};

struct Vec3d {
  double x = 0, y = 0, z = 0;
  friend bool operator==(const Vec3d&, const Vec3d&) = default;
};

/// A float property of a mesh's corners or vertices: texture coordinates,
/// normals, colours or any other channels (docs/cpp-api.md, "Properties").
struct MeshProperty {
  std::string name;         ///< "uv" (width 2), "normal" (3), "color" (3 or 4) by convention, or any
  std::uint32_t width = 0;  ///< floats per element
  bool per_corner = true;   ///< per corner (one element per entry of indices), else per vertex
  std::vector<float> values;
  friend bool operator==(const MeshProperty&, const MeshProperty&) = default;
};

struct Mesh {
  std::vector<Vec3d> vertices;
  /// Concatenated vertex indices of all faces.
  std::vector<std::uint32_t> indices;
  /// Face f uses indices[face_offsets[f] .. face_offsets[f+1]). Always starts with 0.
  std::vector<std::uint32_t> face_offsets{0};
  /// Optional, empty or one per face: the face's group (a material, an OBJ
  /// `usemtl`). A Boolean gives each output face its source face's group and
  /// never merges coplanar faces of different groups (docs/cpp-api.md, "Face groups").
  std::vector<std::uint32_t> face_groups;
  /// Optional names of the groups: group g is called group_names[g] where
  /// that exists and is not empty.
  std::vector<std::string> group_names;
  /// Optional properties. A Boolean gives every output corner each property
  /// any operand has, per corner: kept where the corner is an input vertex,
  /// interpolated linearly in the input face it lies on elsewhere.
  std::vector<MeshProperty> properties;

  std::size_t face_count() const { return face_offsets.size() - 1; }
  std::size_t face_size(std::size_t f) const { return face_offsets[f + 1] - face_offsets[f]; }
  std::span<const std::uint32_t> face(std::size_t f) const { return {indices.data() + face_offsets[f], face_size(f)}; }
  /// Number of triangles a fan triangulation of every face would give.
  std::size_t triangle_count() const {
    std::size_t n = 0;
    for (std::size_t f = 0; f < face_count(); ++f) n += face_size(f) >= 3 ? face_size(f) - 2 : 0;
    return n;
  }
  std::uint32_t add_vertex(Vec3d p) {
    vertices.push_back(p);
    return static_cast<std::uint32_t>(vertices.size() - 1);
  }
  void add_face(std::span<const std::uint32_t> f) {
    indices.insert(indices.end(), f.begin(), f.end());
    face_offsets.push_back(static_cast<std::uint32_t>(indices.size()));
  }
  void add_face(std::initializer_list<std::uint32_t> f) {
    add_face(std::span<const std::uint32_t>(f.begin(), f.size()));
  }
  bool empty() const { return face_count() == 0; }
  friend bool operator==(const Mesh&, const Mesh&) = default;
};

}  // namespace ember
