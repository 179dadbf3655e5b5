// 3MF through lib3mf 1.x (Debian lib3mf-dev): lib3mf does the ZIP/OPC package
// and the XML, this file only maps between its model and ember::Mesh.
//
// lib3mf 1.x exposes a C-style "DLL" interface of reference-counted handles;
// every handle we get is released by Handle, and every call's result is
// checked, with lib3mf's own message in the ember::Error.
#include <Model/COM/NMR_DLLInterfaces.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "ember/error.hpp"
#include "ember/io/mesh_io.hpp"
#include "io/threemf_scan.hpp"
#include "io/writer_support.hpp"

namespace ember {
namespace {

struct Release {
  void operator()(NMR::PLib3MFBase* p) const { NMR::lib3mf_release(p); }
};
/// Owns one lib3mf reference.
using Handle = std::unique_ptr<NMR::PLib3MFBase, Release>;

/// lib3mf's message for the last failed call on `instance`.
std::string last_error(NMR::PLib3MFBase* instance) {
  DWORD code = 0;
  LPCSTR message = nullptr;
  if (instance && NMR::lib3mf_getlasterror(instance, &code, &message) == 0 && message && *message)
    return std::string(message) + " (lib3mf error " + std::to_string(code) + ")";
  return "lib3mf reported an error without a message";
}

void check(LIB3MFRESULT result, NMR::PLib3MFBase* instance, std::string_view name, std::string_view what) {
  if (result != 0) throw Error(std::string(name) + ": 3MF: " + std::string(what) + " failed: " + last_error(instance));
}

Handle new_model() {
  NMR::PLib3MFModel* model = nullptr;
  if (NMR::lib3mf_createmodel(&model) != 0 || !model)
    throw Error("3MF: lib3mf could not create a model (out of memory?)");
  return Handle(model);
}

/// A 3MF affine transform: rows of (linear part | translation), applied to column vectors.
struct Affine {
  std::array<std::array<double, 4>, 3> m{{{1, 0, 0, 0}, {0, 1, 0, 0}, {0, 0, 1, 0}}};

  static Affine from(const NMR::MODELTRANSFORM& t) {
    Affine a;
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 4; ++c) a.m[r][c] = t.m_fFields[r][c];
    return a;
  }
  Vec3d apply(const Vec3d& p) const {
    auto row = [&](int r) { return m[r][0] * p.x + m[r][1] * p.y + m[r][2] * p.z + m[r][3]; };
    return {row(0), row(1), row(2)};
  }
  /// this ∘ inner: first inner, then this.
  Affine after(const Affine& inner) const {
    Affine out;
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 4; ++c) {
        double v = c == 3 ? m[r][3] : 0.0;
        for (int k = 0; k < 3; ++k) v += m[r][k] * inner.m[k][c];
        out.m[r][c] = v;
      }
    return out;
  }
};

/// Appends `object` (a mesh, or components referring to further objects) to
/// `out`, transformed by `to_world`. Components may nest; the depth bound
/// only guards against a malformed file that lib3mf let through.
/// The refusal for a file beyond the ReadOptions limits.
[[noreturn]] void too_large(std::string_view name, const std::string& what) {
  throw Error(
      "3MF: " + what +
          "; refusing to expand it (raise ReadOptions::max_3mf_triangles / max_3mf_instancing, at the "
          "command line --max-3mf-triangles / --max-3mf-instancing, if the file is trusted and memory suffices)",
      {.file = std::string(name)});
}

/// Triangles flattened so far, against the limit (a second guard for files
/// the scan could not follow).
struct Budget {
  std::uint64_t limit = 0, triangles = 0, instances = 0;
  void take(std::uint64_t n, std::string_view name) {
    triangles += n;
    ++instances;
    if (triangles > limit || instances > limit)
      too_large(name, "the build items expand to more than " + std::to_string(limit) +
                          " triangles or object instances (the limit)");
  }
};

void flatten(NMR::PLib3MFModelObjectResource* object, const Affine& to_world, Mesh& out, std::string_view name,
             int depth, Budget& budget) {
  if (depth > 64) throw Error(std::string(name) + ": 3MF: components nest more than 64 levels deep (a cycle?)");
  BOOL is_mesh = 0, is_components = 0;
  check(NMR::lib3mf_object_ismeshobject(object, &is_mesh), object, name, "object type query");
  if (is_mesh) {
    DWORD nv = 0, nt = 0;
    check(NMR::lib3mf_meshobject_getvertexcount(object, &nv), object, name, "vertex count");
    check(NMR::lib3mf_meshobject_gettrianglecount(object, &nt), object, name, "triangle count");
    budget.take(nt, name);
    std::vector<NMR::MODELMESHVERTEX> vertices(nv);
    std::vector<NMR::MODELMESHTRIANGLE> triangles(nt);
    if (nv)
      check(NMR::lib3mf_meshobject_getvertices(object, vertices.data(), nv, nullptr), object, name, "reading vertices");
    if (nt)
      check(NMR::lib3mf_meshobject_gettriangleindices(object, triangles.data(), nt, nullptr), object, name,
            "reading triangles");
    const auto base = static_cast<std::uint32_t>(out.vertices.size());
    for (const NMR::MODELMESHVERTEX& v : vertices)
      out.vertices.push_back(to_world.apply({v.m_fPosition[0], v.m_fPosition[1], v.m_fPosition[2]}));
    for (const NMR::MODELMESHTRIANGLE& t : triangles) {
      for (const DWORD i : t.m_nIndices)
        if (i >= nv)
          throw Error(std::string(name) + ": 3MF: a triangle uses vertex " + std::to_string(i) + " of an object with " +
                      std::to_string(nv) + " vertices");
      out.add_face({base + t.m_nIndices[0], base + t.m_nIndices[1], base + t.m_nIndices[2]});
    }
    return;
  }
  check(NMR::lib3mf_object_iscomponentsobject(object, &is_components), object, name, "object type query");
  if (!is_components) throw Error(std::string(name) + ": 3MF: an object is neither a mesh nor components");
  DWORD count = 0;
  check(NMR::lib3mf_componentsobject_getcomponentcount(object, &count), object, name, "component count");
  for (DWORD i = 0; i < count; ++i) {
    NMR::PLib3MFModelComponent* raw = nullptr;
    check(NMR::lib3mf_componentsobject_getcomponent(object, i, &raw), object, name, "reading a component");
    const Handle component(raw);
    NMR::MODELTRANSFORM t{};
    check(NMR::lib3mf_component_gettransform(raw, &t), raw, name, "component transform");
    NMR::PLib3MFModelObjectResource* child = nullptr;
    check(NMR::lib3mf_component_getobjectresource(raw, &child), raw, name, "component object");
    const Handle child_handle(child);
    flatten(child, to_world.after(Affine::from(t)), out, name, depth + 1, budget);
  }
}

/// 64-bit FNV-1a over the mesh's coordinates (bit patterns) and indices.
std::uint64_t content_hash(const Mesh& mesh, std::uint64_t seed) {
  std::uint64_t h = 0xcbf29ce484222325ull ^ seed;
  const auto mix = [&h](const void* p, std::size_t n) {
    for (std::size_t i = 0; i < n; ++i) h = (h ^ static_cast<const unsigned char*>(p)[i]) * 0x100000001b3ull;
  };
  mix(mesh.vertices.data(), mesh.vertices.size() * sizeof(Vec3d));
  mix(mesh.indices.data(), mesh.indices.size() * sizeof(std::uint32_t));
  mix(mesh.face_offsets.data(), mesh.face_offsets.size() * sizeof(std::uint32_t));
  return h;
}

/// A UUID (RFC 4122 layout, version 8: custom) made from two hashes, so that
/// the same meshes always give the same file. lib3mf would otherwise draw
/// random UUIDs and two identical runs would differ byte for byte.
std::string derived_uuid(std::uint64_t hi, std::uint64_t lo) {
  hi = (hi & ~0xf000ull) | 0x8000ull;              // version 8
  lo = (lo & ~(0xc0ull << 56)) | (0x80ull << 56);  // variant 10
  char buf[40];
  std::snprintf(buf, sizeof buf, "%08x-%04x-%04x-%04x-%012llx", static_cast<unsigned>(hi >> 32),
                static_cast<unsigned>((hi >> 16) & 0xffff), static_cast<unsigned>(hi & 0xffff),
                static_cast<unsigned>(lo >> 48), static_cast<unsigned long long>(lo & 0xffffffffffffull));
  return buf;
}

/// Adds `mesh` to `model` as one mesh object with one build item; their
/// UUIDs derive from the mesh, its position `index` and `file_hash`.
void add_object(NMR::PLib3MFModel* model, const Mesh& mesh, std::size_t index, std::uint64_t file_hash) {
  io_detail::check_mesh_for_writing(mesh, "3MF");
  std::vector<NMR::MODELMESHVERTEX> vertices;
  vertices.reserve(mesh.vertices.size());
  constexpr double kFloatMax = std::numeric_limits<float>::max();
  for (const Vec3d& p : mesh.vertices) {
    if (!(std::abs(p.x) <= kFloatMax && std::abs(p.y) <= kFloatMax && std::abs(p.z) <= kFloatMax))
      throw Error("3MF: a vertex coordinate is not finite or exceeds single precision; 3MF cannot store it");
    vertices.push_back({{static_cast<float>(p.x), static_cast<float>(p.y), static_cast<float>(p.z)}});
  }
  std::vector<NMR::MODELMESHTRIANGLE> triangles;
  triangles.reserve(mesh.triangle_count());
  for (std::size_t f = 0; f < mesh.face_count(); ++f) {
    const auto face = mesh.face(f);
    for (std::size_t i = 1; i + 1 < face.size(); ++i) triangles.push_back({{face[0], face[i], face[i + 1]}});
  }
  NMR::PLib3MFModelMeshObject* object_raw = nullptr;
  check(NMR::lib3mf_model_addmeshobject(model, &object_raw), model, "output", "adding the mesh");
  const Handle object(object_raw);
  // lib3mf rejects empty geometry arrays; an empty result is an object without triangles.
  if (!vertices.empty())
    check(NMR::lib3mf_meshobject_setgeometry(object_raw, vertices.data(), static_cast<DWORD>(vertices.size()),
                                             triangles.data(), static_cast<DWORD>(triangles.size())),
          object_raw, "output", "setting the geometry");
  NMR::PLib3MFModelBuildItem* item_raw = nullptr;
  check(NMR::lib3mf_model_addbuilditem(model, object_raw, nullptr, &item_raw), model, "output",
        "adding the build item");
  const Handle item(item_raw);
  const std::uint64_t h = content_hash(mesh, index) ^ file_hash;
  check(NMR::lib3mf_object_setuuidutf8(object_raw, derived_uuid(h, h * 0x9E3779B97F4A7C15ull + 1).c_str()), object_raw,
        "output", "setting the object UUID");
  check(NMR::lib3mf_builditem_setuuidutf8(item_raw, derived_uuid(h, h * 0x9E3779B97F4A7C15ull + 2).c_str()), item_raw,
        "output", "setting the build item UUID");
}

}  // namespace

std::vector<Mesh> read_3mf(std::string_view bytes, std::string_view name) {
  return read_3mf(bytes, name, ReadOptions{});
}

std::vector<Mesh> read_3mf(std::string_view bytes, std::string_view name, const ReadOptions& options) {
  // lib3mf resolves components instance by instance (exponential time in the
  // nesting depth of a component bomb), so the expansion is sized first.
  if (const auto e = io_detail::scan_3mf_expansion(bytes)) {
    const std::string sizes = "the build items expand to " + std::to_string(e->expanded_triangles) + " triangles in " +
                              std::to_string(e->instances) + " object instances (the file stores " +
                              std::to_string(e->stored_triangles) + " triangles)";
    if (e->expanded_triangles > options.max_3mf_triangles || e->instances > options.max_3mf_triangles)
      too_large(name, sizes + ", more than the limit of " + std::to_string(options.max_3mf_triangles));
    const std::uint64_t stored = std::max<std::uint64_t>(e->stored_triangles, 1);
    const std::uint64_t expanded = std::max(e->expanded_triangles, e->instances);
    if (expanded > 1'000'000 && expanded / stored >= options.max_3mf_instancing)
      too_large(name, sizes + ", more than " + std::to_string(options.max_3mf_instancing) +
                          " times what it stores (components nested in components)");
  }
  const Handle model = new_model();
  NMR::PLib3MFModelReader* reader_raw = nullptr;
  check(NMR::lib3mf_model_queryreader(model.get(), "3mf", &reader_raw), model.get(), name, "creating a reader");
  const Handle reader(reader_raw);
  // lib3mf takes a non-const buffer but only reads it.
  std::vector<BYTE> buffer(bytes.begin(), bytes.end());
  if (NMR::lib3mf_reader_readfrombuffer(reader_raw, buffer.data(), buffer.size()) != 0)
    throw Error(std::string(name) + ": not a readable 3MF file: " + last_error(reader_raw));
  buffer = {};

  NMR::PLib3MFModelBuildItemIterator* items_raw = nullptr;
  check(NMR::lib3mf_model_getbuilditems(model.get(), &items_raw), model.get(), name, "listing build items");
  const Handle items(items_raw);
  std::vector<Mesh> meshes;
  Budget budget{options.max_3mf_triangles};
  for (BOOL more = 0; NMR::lib3mf_builditemiterator_movenext(items_raw, &more) == 0 && more;) {
    NMR::PLib3MFModelBuildItem* item_raw = nullptr;
    check(NMR::lib3mf_builditemiterator_getcurrent(items_raw, &item_raw), items_raw, name, "reading a build item");
    const Handle item(item_raw);
    NMR::MODELTRANSFORM t{};
    check(NMR::lib3mf_builditem_getobjecttransform(item_raw, &t), item_raw, name, "build item transform");
    NMR::PLib3MFModelObjectResource* object_raw = nullptr;
    check(NMR::lib3mf_builditem_getobjectresource(item_raw, &object_raw), item_raw, name, "build item object");
    const Handle object(object_raw);
    Mesh mesh;
    flatten(object_raw, Affine::from(t), mesh, name, 0, budget);
    meshes.push_back(std::move(mesh));
  }
  if (meshes.empty()) throw Error(std::string(name) + ": the 3MF file has no build items, so no object to read");
  return meshes;
}

std::string write_3mf(const Mesh& mesh) { return write_3mf(std::span<const Mesh>(&mesh, 1)); }

std::string write_3mf(std::span<const Mesh> meshes) {
  const Handle model = new_model();
  check(NMR::lib3mf_model_setunit(model.get(), NMR::MODELUNIT_MILLIMETER), model.get(), "output", "setting the unit");
  std::uint64_t file_hash = 0x3a5f;
  for (std::size_t i = 0; i < meshes.size(); ++i) file_hash = file_hash * 31 + content_hash(meshes[i], 0x77 + i);
  for (std::size_t i = 0; i < meshes.size(); ++i) add_object(model.get(), meshes[i], i, file_hash);
  check(NMR::lib3mf_model_setbuilduuidutf8(model.get(), derived_uuid(file_hash, ~file_hash).c_str()), model.get(),
        "output", "setting the build UUID");
  NMR::PLib3MFModelWriter* writer_raw = nullptr;
  check(NMR::lib3mf_model_querywriter(model.get(), "3mf", &writer_raw), model.get(), "output", "creating a writer");
  const Handle writer(writer_raw);
  ULONG64 size = 0;
  check(NMR::lib3mf_writer_getstreamsize(writer_raw, &size), writer_raw, "output", "sizing the package");
  std::string bytes(static_cast<std::size_t>(size), '\0');
  check(NMR::lib3mf_writer_writetobuffer(writer_raw, reinterpret_cast<BYTE*>(bytes.data()), size), writer_raw, "output",
        "writing the package");
  return bytes;
}

}  // namespace ember
