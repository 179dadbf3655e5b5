// glTF 2.0 (.gltf JSON, .glb binary) through tinygltf: the triangles of every
// mesh node of the scene, node transforms applied, as one mesh whose face
// groups are the primitives' materials; written as one node with one
// primitive per face group. tinygltf parses; every count, index and offset it
// hands over is checked here against the buffers before it is used.
#include <tiny_gltf.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

#include "ember/error.hpp"
#include "ember/io/mesh_io.hpp"
#include "io/gltf.hpp"
#include "io/writer_support.hpp"

namespace ember {
namespace {

using Matrix = std::array<double, 16>;  // column-major, as glTF stores it

[[noreturn]] void fail(std::string_view name, const std::string& what) {
  throw Error(what, {.file = std::string(name)});
}

Matrix multiply(const Matrix& a, const Matrix& b) {
  Matrix c{};
  for (int col = 0; col < 4; ++col)
    for (int row = 0; row < 4; ++row)
      for (int k = 0; k < 4; ++k) c[col * 4 + row] += a[k * 4 + row] * b[col * 4 + k];
  return c;
}

/// A node's local transform: its matrix, or translation * rotation * scale.
Matrix local_transform(const tinygltf::Node& node, std::string_view name) {
  Matrix m{1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};
  if (!node.matrix.empty()) {
    if (node.matrix.size() != 16) fail(name, "a node's matrix must have 16 numbers");
    std::copy(node.matrix.begin(), node.matrix.end(), m.begin());
  } else {
    const auto& t = node.translation;
    const auto& r = node.rotation;
    const auto& s = node.scale;
    if ((!t.empty() && t.size() != 3) || (!r.empty() && r.size() != 4) || (!s.empty() && s.size() != 3))
      fail(name, "a node's translation, rotation or scale has the wrong length");
    const double x = r.empty() ? 0 : r[0], y = r.empty() ? 0 : r[1], z = r.empty() ? 0 : r[2], w = r.empty() ? 1 : r[3];
    const std::array<double, 3> sc{s.empty() ? 1 : s[0], s.empty() ? 1 : s[1], s.empty() ? 1 : s[2]};
    const std::array<std::array<double, 3>, 3> rot{
        {{1 - 2 * (y * y + z * z), 2 * (x * y + z * w), 2 * (x * z - y * w)},
         {2 * (x * y - z * w), 1 - 2 * (x * x + z * z), 2 * (y * z + x * w)},
         {2 * (x * z + y * w), 2 * (y * z - x * w), 1 - 2 * (x * x + y * y)}}};
    for (int col = 0; col < 3; ++col)
      for (int row = 0; row < 3; ++row) m[col * 4 + row] = rot[col][row] * sc[col];
    for (int row = 0; row < 3; ++row) m[12 + row] = t.empty() ? 0 : t[row];
  }
  for (const double v : m)
    if (!std::isfinite(v)) fail(name, "a node's transform is not finite");
  return m;
}

/// The elements of an accessor, checked against its buffer view and buffer.
struct AccessorView {
  const unsigned char* data = nullptr;
  std::size_t count = 0, stride = 0, element = 0;
  int component = 0;
};

std::size_t component_size(int type) {
  switch (type) {
    case TINYGLTF_COMPONENT_TYPE_BYTE:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return 1;
    case TINYGLTF_COMPONENT_TYPE_SHORT:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: return 2;
    case TINYGLTF_COMPONENT_TYPE_INT:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT:
    case TINYGLTF_COMPONENT_TYPE_FLOAT: return 4;
    case TINYGLTF_COMPONENT_TYPE_DOUBLE: return 8;
    default: return 0;
  }
}

AccessorView view_of(const tinygltf::Model& model, int index, int components, std::string_view name, const char* what) {
  if (index < 0 || static_cast<std::size_t>(index) >= model.accessors.size())
    fail(name, std::string(what) + " accessor " + std::to_string(index) + " does not exist");
  const tinygltf::Accessor& a = model.accessors[static_cast<std::size_t>(index)];
  if (a.sparse.isSparse) fail(name, std::string(what) + ": sparse accessors are not supported");
  if (tinygltf::GetNumComponentsInType(static_cast<std::uint32_t>(a.type)) != components)
    fail(name, std::string(what) + " accessor " + std::to_string(index) + " has the wrong type");
  AccessorView v;
  v.component = a.componentType;
  v.element = component_size(a.componentType) * static_cast<std::size_t>(components);
  if (v.element == 0) fail(name, std::string(what) + " accessor " + std::to_string(index) + ": unknown component type");
  v.count = a.count;
  if (a.bufferView < 0 || static_cast<std::size_t>(a.bufferView) >= model.bufferViews.size())
    fail(name, std::string(what) + " accessor " + std::to_string(index) + " has no buffer view");
  const tinygltf::BufferView& bv = model.bufferViews[static_cast<std::size_t>(a.bufferView)];
  if (bv.buffer < 0 || static_cast<std::size_t>(bv.buffer) >= model.buffers.size())
    fail(name, "buffer view " + std::to_string(a.bufferView) + " has no buffer");
  const std::vector<unsigned char>& buffer = model.buffers[static_cast<std::size_t>(bv.buffer)].data;
  v.stride = bv.byteStride ? bv.byteStride : v.element;
  // Overflow-free: every term is checked against the sizes before it is added.
  const bool fits = bv.byteOffset <= buffer.size() && bv.byteLength <= buffer.size() - bv.byteOffset &&
                    a.byteOffset <= bv.byteLength && v.stride >= v.element &&
                    (v.count == 0 || (v.count - 1 <= (bv.byteLength - a.byteOffset) / v.stride &&
                                      (v.count - 1) * v.stride + v.element <= bv.byteLength - a.byteOffset));
  if (!fits)
    fail(name, std::string(what) + " accessor " + std::to_string(index) + " (" + std::to_string(v.count) +
                   " elements) reaches past its buffer");
  v.data = buffer.data() + bv.byteOffset + a.byteOffset;
  return v;
}

std::uint32_t index_at(const AccessorView& v, std::size_t i) {
  const unsigned char* p = v.data + i * v.stride;
  switch (v.component) {
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return *p;
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
      std::uint16_t x;
      std::memcpy(&x, p, 2);
      return x;
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: {
      std::uint32_t x;
      std::memcpy(&x, p, 4);
      return x;
    }
    default: return UINT32_MAX;
  }
}

/// What the scene's traversal collects: one mesh, and how many triangles the
/// instances add (a node tree that instances one mesh many times is refused
/// beyond ReadOptions' limit, as a 3MF component bomb is).
struct Collector {
  const tinygltf::Model& model;
  std::string_view name;
  std::uint64_t max_triangles;
  Mesh mesh;
  std::vector<std::uint32_t> groups;
  std::vector<float> uv, normal;  // per vertex of `mesh`, zeros where a primitive has none
  bool any_uv = false, any_normal = false;
  bool any_material = false;
  std::uint64_t triangles = 0;
  /// Primitives of one mesh instance that share a POSITION accessor share
  /// its vertices (ember writes one accessor for all its primitives).
  std::size_t instance = 0;
  std::map<std::pair<std::size_t, int>, std::uint32_t> base_of;

  void primitive(const tinygltf::Primitive& p, const Matrix& m) {
    if (p.mode != TINYGLTF_MODE_TRIANGLES && p.mode != TINYGLTF_MODE_TRIANGLE_STRIP &&
        p.mode != TINYGLTF_MODE_TRIANGLE_FAN && p.mode != -1)
      return;  // points and lines bound no volume
    if (p.material >= 0 && static_cast<std::size_t>(p.material) >= model.materials.size())
      fail(name, "material " + std::to_string(p.material) + " does not exist");
    const auto pos = p.attributes.find("POSITION");
    if (pos == p.attributes.end()) fail(name, "a triangle primitive has no POSITION attribute");
    const AccessorView v = view_of(model, pos->second, 3, name, "POSITION");
    if (v.component != TINYGLTF_COMPONENT_TYPE_FLOAT) fail(name, "POSITION must be float (glTF 2.0)");
    std::vector<std::uint32_t> order;
    if (p.indices >= 0) {
      const AccessorView iv = view_of(model, p.indices, 1, name, "indices");
      if (iv.component == TINYGLTF_COMPONENT_TYPE_BYTE || iv.component == TINYGLTF_COMPONENT_TYPE_SHORT ||
          iv.component == TINYGLTF_COMPONENT_TYPE_INT || iv.component == TINYGLTF_COMPONENT_TYPE_FLOAT ||
          iv.component == TINYGLTF_COMPONENT_TYPE_DOUBLE)
        fail(name, "indices must be unsigned byte, short or int");
      order.resize(iv.count);
      for (std::size_t i = 0; i < iv.count; ++i) {
        order[i] = index_at(iv, i);
        if (order[i] >= v.count)
          fail(name,
               "index " + std::to_string(order[i]) + " is out of range (" + std::to_string(v.count) + " positions)");
      }
    } else {
      order.resize(v.count);
      for (std::size_t i = 0; i < v.count; ++i) order[i] = static_cast<std::uint32_t>(i);
    }
    const std::size_t n = order.size();
    const std::uint64_t tris = p.mode == TINYGLTF_MODE_TRIANGLES || p.mode == -1 ? n / 3 : (n >= 3 ? n - 2 : 0);
    triangles += tris;
    if (triangles > max_triangles)
      fail(name, "the scene's nodes instance more than " + std::to_string(max_triangles) +
                     " triangles; raise the limit (ReadOptions::max_3mf_triangles, CLI --max-3mf-triangles) if "
                     "the file is trusted");
    if (mesh.vertices.size() + v.count > UINT32_MAX) fail(name, "too many vertices (at most 2^32-1 supported)");
    const auto [known, added] =
        base_of.emplace(std::pair{instance, pos->second}, static_cast<std::uint32_t>(mesh.vertices.size()));
    const std::uint32_t base = known->second;
    for (std::size_t i = 0; added && i < v.count; ++i) {
      float xyz[3];
      std::memcpy(xyz, v.data + i * v.stride, 12);
      const double x = xyz[0], y = xyz[1], z = xyz[2];
      const Vec3d q{m[0] * x + m[4] * y + m[8] * z + m[12], m[1] * x + m[5] * y + m[9] * z + m[13],
                    m[2] * x + m[6] * y + m[10] * z + m[14]};
      if (!std::isfinite(q.x) || !std::isfinite(q.y) || !std::isfinite(q.z))
        fail(name, "position " + std::to_string(i) + " is not finite");
      mesh.vertices.push_back(q);
    }
    if (added) attributes(p, m, v.count);
    // A mirroring transform turns faces inside out; glTF flips the winding then.
    const double det =
        m[0] * (m[5] * m[10] - m[9] * m[6]) - m[4] * (m[1] * m[10] - m[9] * m[2]) + m[8] * (m[1] * m[6] - m[5] * m[2]);
    const auto add = [&](std::uint32_t a, std::uint32_t b, std::uint32_t c) {
      if (det < 0) std::swap(b, c);
      mesh.add_face({base + a, base + b, base + c});
      groups.push_back(p.material < 0 ? UINT32_MAX : static_cast<std::uint32_t>(p.material));
    };
    if (p.mode == TINYGLTF_MODE_TRIANGLES || p.mode == -1) {
      for (std::size_t i = 0; i + 2 < n; i += 3) add(order[i], order[i + 1], order[i + 2]);
    } else if (p.mode == TINYGLTF_MODE_TRIANGLE_STRIP) {
      for (std::size_t i = 0; i + 2 < n; ++i)
        i % 2 == 0 ? add(order[i], order[i + 1], order[i + 2]) : add(order[i + 1], order[i], order[i + 2]);
    } else {
      for (std::size_t i = 1; i + 1 < n; ++i) add(order[0], order[i], order[i + 1]);
    }
    any_material |= p.material >= 0;
  }

  /// TEXCOORD_0 and NORMAL of a primitive's `count` new vertices (normals
  /// through the inverse transpose of the node's transform).
  void attributes(const tinygltf::Primitive& p, const Matrix& m, std::size_t count) {
    const auto read = [&](const char* attribute, int width, std::vector<float>& into, bool& any) {
      const auto it = p.attributes.find(attribute);
      const std::size_t at = into.size();
      into.resize(at + count * static_cast<std::size_t>(width), 0.0f);
      if (it == p.attributes.end()) return;
      const AccessorView a = view_of(model, it->second, width, name, attribute);
      if (a.component != TINYGLTF_COMPONENT_TYPE_FLOAT) fail(name, std::string(attribute) + " must be float");
      if (a.count != count) fail(name, std::string(attribute) + " has a different count than POSITION");
      for (std::size_t i = 0; i < count; ++i) {
        std::memcpy(into.data() + at + i * static_cast<std::size_t>(width), a.data + i * a.stride,
                    4 * static_cast<std::size_t>(width));
        for (int c = 0; c < width; ++c)
          if (!std::isfinite(into[at + i * static_cast<std::size_t>(width) + static_cast<std::size_t>(c)]))
            fail(name, std::string(attribute) + " value " + std::to_string(i) + " is not finite");
      }
      any = true;
    };
    const std::size_t first_normal = normal.size();
    read("TEXCOORD_0", 2, uv, any_uv);
    read("NORMAL", 3, normal, any_normal);
    // n' = C n with C the cofactor matrix of the linear part A (A^-T = C / det A).
    const auto a = [&](int r, int col) { return m[static_cast<std::size_t>(col * 4 + r)]; };
    const double C[3][3] = {{a(1, 1) * a(2, 2) - a(1, 2) * a(2, 1), a(1, 2) * a(2, 0) - a(1, 0) * a(2, 2),
                             a(1, 0) * a(2, 1) - a(1, 1) * a(2, 0)},
                            {a(0, 2) * a(2, 1) - a(0, 1) * a(2, 2), a(0, 0) * a(2, 2) - a(0, 2) * a(2, 0),
                             a(0, 1) * a(2, 0) - a(0, 0) * a(2, 1)},
                            {a(0, 1) * a(1, 2) - a(0, 2) * a(1, 1), a(0, 2) * a(1, 0) - a(0, 0) * a(1, 2),
                             a(0, 0) * a(1, 1) - a(0, 1) * a(1, 0)}};
    const double det = a(0, 0) * C[0][0] + a(0, 1) * C[0][1] + a(0, 2) * C[0][2];
    for (std::size_t i = first_normal; i + 2 < normal.size(); i += 3) {
      const double n[3] = {normal[i], normal[i + 1], normal[i + 2]};
      double t[3];
      for (int r = 0; r < 3; ++r) t[r] = C[r][0] * n[0] + C[r][1] * n[1] + C[r][2] * n[2];
      const double len = std::sqrt(t[0] * t[0] + t[1] * t[1] + t[2] * t[2]);
      const double sign = len > 0 ? (det < 0 ? -1.0 : 1.0) / len : 0.0;
      for (int k = 0; k < 3; ++k) normal[i + static_cast<std::size_t>(k)] = static_cast<float>(t[k] * sign);
    }
  }

  void node(int index, const Matrix& parent, int depth) {
    if (index < 0 || static_cast<std::size_t>(index) >= model.nodes.size())
      fail(name, "node " + std::to_string(index) + " does not exist");
    // glTF node trees are acyclic and shallow; a deeper chain is a loop.
    if (depth > 256) fail(name, "the node hierarchy is deeper than 256 levels (a cycle?)");
    const tinygltf::Node& n = model.nodes[static_cast<std::size_t>(index)];
    const Matrix m = multiply(parent, local_transform(n, name));
    if (n.mesh >= 0) {
      if (static_cast<std::size_t>(n.mesh) >= model.meshes.size())
        fail(name, "mesh " + std::to_string(n.mesh) + " does not exist");
      ++instance;
      for (const tinygltf::Primitive& p : model.meshes[static_cast<std::size_t>(n.mesh)].primitives) primitive(p, m);
    }
    for (const int child : n.children) node(child, m, depth + 1);
  }
};

/// File access for external buffers: only below `base` (the file's folder),
/// and none when reading from memory. (tinygltf's own would expand paths with
/// the shell's rules.)
struct FileAccess {
  std::filesystem::path base;
  bool allowed = false;
};

bool file_exists(const std::string& path, void* user) {
  const auto* fa = static_cast<FileAccess*>(user);
  return fa->allowed && std::filesystem::is_regular_file(path);
}
std::string expand_path(const std::string& path, void*) { return path; }
bool read_whole_file(std::vector<unsigned char>* out, std::string* err, const std::string& path, void* user) {
  const auto* fa = static_cast<FileAccess*>(user);
  if (!fa->allowed) {
    *err = "external file '" + path + "' cannot be read from memory; read the .gltf file by its path";
    return false;
  }
  std::ifstream f(path, std::ios::binary);
  if (!f) {
    *err = "cannot open '" + path + "'";
    return false;
  }
  out->assign(std::istreambuf_iterator<char>(f), std::istreambuf_iterator<char>());
  return true;
}
bool write_whole_file(std::string* err, const std::string&, const std::vector<unsigned char>&, void*) {
  *err = "ember writes no side files";
  return false;
}
// Textures are not needed for the geometry: images are kept undecoded.
bool skip_image(tinygltf::Image*, const int, std::string*, std::string*, int, int, const unsigned char*, int, void*) {
  return true;
}

}  // namespace

namespace io_detail {

Mesh read_gltf(std::string_view bytes, std::string_view name, bool binary, const std::filesystem::path& base,
               std::uint64_t max_triangles) {
  tinygltf::TinyGLTF loader;
  FileAccess access{base, !base.empty()};
  loader.SetFsCallbacks({&file_exists, &expand_path, &read_whole_file, &write_whole_file, &access});
  loader.SetImageLoader(&skip_image, nullptr);
  tinygltf::Model model;
  std::string err, warn;
  const auto* data = reinterpret_cast<const unsigned char*>(bytes.data());
  if (bytes.size() > UINT32_MAX) fail(name, "file too large for glTF (over 4 GiB)");
  const std::string dir = base.string();
  const bool ok =
      binary
          ? loader.LoadBinaryFromMemory(&model, &err, &warn, data, static_cast<unsigned int>(bytes.size()), dir)
          : loader.LoadASCIIFromString(&model, &err, &warn, bytes.data(), static_cast<unsigned int>(bytes.size()), dir);
  if (!ok) {
    while (!err.empty() && (err.back() == '\n' || err.back() == ' ')) err.pop_back();
    fail(name,
         std::string("not a valid ") + (binary ? "GLB" : "glTF") + " file: " + (err.empty() ? "parse error" : err));
  }
  Collector c{model, name, max_triangles};
  const Matrix identity{1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};
  if (!model.scenes.empty()) {
    const int s = model.defaultScene >= 0 ? model.defaultScene : 0;
    if (static_cast<std::size_t>(s) >= model.scenes.size()) fail(name, "the default scene does not exist");
    for (const int n : model.scenes[static_cast<std::size_t>(s)].nodes) c.node(n, identity, 0);
  } else {
    // No scene: every mesh once, untransformed (the spec leaves it to the reader).
    for (const tinygltf::Mesh& m : model.meshes)
      for (const tinygltf::Primitive& p : m.primitives) c.primitive(p, identity);
  }
  if (c.any_uv) c.mesh.properties.push_back({"uv", 2, false, std::move(c.uv)});
  if (c.any_normal) c.mesh.properties.push_back({"normal", 3, false, std::move(c.normal)});
  if (c.any_material) {
    c.mesh.group_names.resize(model.materials.size());
    for (std::size_t i = 0; i < model.materials.size(); ++i) c.mesh.group_names[i] = model.materials[i].name;
    const auto unnamed = static_cast<std::uint32_t>(model.materials.size());
    bool any_without = false;
    for (std::uint32_t& g : c.groups)
      if (g == UINT32_MAX) g = unnamed, any_without = true;
    if (any_without) c.mesh.group_names.emplace_back();
    c.mesh.face_groups = std::move(c.groups);
  }
  return std::move(c.mesh);
}

}  // namespace io_detail

Mesh read_gltf(std::string_view bytes, std::string_view name, bool binary) {
  return io_detail::read_gltf(bytes, name, binary, {}, ReadOptions{}.max_3mf_triangles);
}

std::string write_gltf(const Mesh& mesh, bool binary) {
  io_detail::check_mesh_for_writing(mesh, binary ? "GLB" : "glTF");
  // glTF attributes are per vertex: with "uv" or "normal" properties each
  // distinct (vertex, uv, normal) of a corner is one glTF vertex (seams split).
  const MeshProperty *uv = nullptr, *normal = nullptr;
  for (const MeshProperty& p : mesh.properties) {
    if (p.name == "uv" && p.width == 2) uv = &p;
    if (p.name == "normal" && p.width == 3) normal = &p;
  }
  std::vector<std::uint32_t> vertex_of(mesh.indices.size());
  std::vector<Vec3d> gltf_vertices;
  std::vector<float> uvs, normals;
  if (!uv && !normal) {
    vertex_of = mesh.indices;
    gltf_vertices = mesh.vertices;
  } else {
    std::map<std::pair<std::uint32_t, std::array<float, 5>>, std::uint32_t> index;
    for (std::size_t c = 0; c < mesh.indices.size(); ++c) {
      const std::uint32_t v = mesh.indices[c];
      std::array<float, 5> key{};
      const auto take = [&](const MeshProperty* p, std::size_t at) {
        if (!p) return;
        const std::size_t e = p->per_corner ? c : v;
        for (std::uint32_t k = 0; k < p->width; ++k) key[at + k] = p->values[e * p->width + k];
      };
      take(uv, 0);
      take(normal, 2);
      const auto [it, added] = index.emplace(std::pair{v, key}, static_cast<std::uint32_t>(gltf_vertices.size()));
      if (added) {
        gltf_vertices.push_back(mesh.vertices[v]);
        if (uv) uvs.insert(uvs.end(), key.begin(), key.begin() + 2);
        if (normal) normals.insert(normals.end(), key.begin() + 2, key.end());
      }
      vertex_of[c] = it->second;
    }
  }
  // Faces fan-triangulated, grouped by face group in group order (one
  // primitive per group), all sharing one set of vertex accessors.
  std::map<std::uint32_t, std::vector<std::uint32_t>> by_group;
  for (std::size_t f = 0; f < mesh.face_count(); ++f) {
    const std::uint32_t c0 = mesh.face_offsets[f];
    std::vector<std::uint32_t>& tris = by_group[mesh.face_groups.empty() ? 0 : mesh.face_groups[f]];
    for (std::size_t i = 1; i + 1 < mesh.face_size(f); ++i)
      tris.insert(tris.end(), {vertex_of[c0], vertex_of[c0 + i], vertex_of[c0 + i + 1]});
  }
  tinygltf::Model model;
  model.asset.version = "2.0";
  model.asset.generator = "ember";
  tinygltf::Buffer buffer;
  std::vector<unsigned char>& bytes = buffer.data;
  const auto append = [&](const void* p, std::size_t n) {
    const auto* b = static_cast<const unsigned char*>(p);
    bytes.insert(bytes.end(), b, b + n);
  };
  std::vector<double> lo(3, 0.0), hi(3, 0.0);
  for (std::size_t i = 0; i < gltf_vertices.size(); ++i) {
    const Vec3d& p = gltf_vertices[i];
    const float xyz[3] = {static_cast<float>(p.x), static_cast<float>(p.y), static_cast<float>(p.z)};
    append(xyz, sizeof xyz);
    for (int a = 0; a < 3; ++a) {
      lo[a] = i == 0 ? xyz[a] : std::min(lo[a], static_cast<double>(xyz[a]));
      hi[a] = i == 0 ? xyz[a] : std::max(hi[a], static_cast<double>(xyz[a]));
    }
  }
  model.bufferViews.push_back({});
  model.bufferViews[0].buffer = 0;
  model.bufferViews[0].byteLength = bytes.size();
  model.bufferViews[0].target = TINYGLTF_TARGET_ARRAY_BUFFER;
  tinygltf::Accessor positions;
  positions.bufferView = 0;
  positions.componentType = TINYGLTF_COMPONENT_TYPE_FLOAT;
  positions.type = TINYGLTF_TYPE_VEC3;
  positions.count = gltf_vertices.size();
  positions.minValues = lo;
  positions.maxValues = hi;
  model.accessors.push_back(positions);
  // TEXCOORD_0 and NORMAL, one buffer view each, accessors 1 and 2 when present.
  std::map<std::string, int> attributes{{"POSITION", 0}};
  for (const auto& [name, values, width] : {std::tuple{"TEXCOORD_0", &uvs, 2}, std::tuple{"NORMAL", &normals, 3}}) {
    if (values->empty()) continue;
    tinygltf::BufferView view;
    view.buffer = 0;
    view.byteOffset = bytes.size();
    append(values->data(), values->size() * 4);
    view.byteLength = values->size() * 4;
    view.target = TINYGLTF_TARGET_ARRAY_BUFFER;
    model.bufferViews.push_back(view);
    tinygltf::Accessor a;
    a.bufferView = static_cast<int>(model.bufferViews.size() - 1);
    a.componentType = TINYGLTF_COMPONENT_TYPE_FLOAT;
    a.type = width == 2 ? TINYGLTF_TYPE_VEC2 : TINYGLTF_TYPE_VEC3;
    a.count = values->size() / static_cast<std::size_t>(width);
    model.accessors.push_back(a);
    attributes[name] = static_cast<int>(model.accessors.size() - 1);
  }
  tinygltf::Mesh out;
  for (const auto& [group, tris] : by_group) {
    tinygltf::BufferView view;
    view.buffer = 0;
    view.byteOffset = bytes.size();
    append(tris.data(), tris.size() * 4);
    view.byteLength = tris.size() * 4;
    view.target = TINYGLTF_TARGET_ELEMENT_ARRAY_BUFFER;
    model.bufferViews.push_back(view);
    tinygltf::Accessor indices;
    indices.bufferView = static_cast<int>(model.bufferViews.size() - 1);
    indices.componentType = TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT;
    indices.type = TINYGLTF_TYPE_SCALAR;
    indices.count = tris.size();
    model.accessors.push_back(indices);
    tinygltf::Primitive p;
    p.attributes = attributes;
    p.indices = static_cast<int>(model.accessors.size() - 1);
    p.mode = TINYGLTF_MODE_TRIANGLES;
    if (!mesh.face_groups.empty()) {
      tinygltf::Material material;
      material.name = group < mesh.group_names.size() && !mesh.group_names[group].empty()
                          ? mesh.group_names[group]
                          : "group_" + std::to_string(group);
      model.materials.push_back(material);
      p.material = static_cast<int>(model.materials.size() - 1);
    }
    out.primitives.push_back(p);
  }
  model.buffers.push_back(std::move(buffer));
  model.meshes.push_back(out);
  tinygltf::Node node;
  node.mesh = 0;
  model.nodes.push_back(node);
  tinygltf::Scene scene;
  scene.nodes = {0};
  model.scenes.push_back(scene);
  model.defaultScene = 0;
  tinygltf::TinyGLTF writer;
  std::ostringstream stream;
  // embedImages, embedBuffers: one self-contained file either way.
  if (!writer.WriteGltfSceneToStream(&model, stream, /*prettyPrint=*/!binary, binary))
    throw Error(std::string("cannot write ") + (binary ? "GLB" : "glTF"));
  return stream.str();
}

}  // namespace ember
