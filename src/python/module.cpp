// The Python module `ember`: exact mesh Booleans and mesh files over numpy.
//
//   import ember
//   v, f = ember.difference((v1, f1), trimesh_mesh, threads=0)
//
// A mesh is a (vertices, faces) pair: float64 (n, 3) and integer (m, k >= 3)
// arrays, or any object with .vertices and .faces (trimesh.Trimesh). Results
// are (vertices float64 (n, 3), faces int64 (m, 3)) tuples: ember's convex
// output is already a triangle mesh; files read as polygons are fan-triangulated.
// Errors are ember.Error (a ValueError) with the library's message.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <algorithm>
#include <cstdint>
#include <string>
#include <type_traits>
#include <vector>

#include "ember/boolean.hpp"
#include "ember/csg.hpp"
#include "ember/error.hpp"
#include "ember/io/mesh_io.hpp"

namespace py = pybind11;

namespace {

std::string shape_of(const py::array& a) {
  std::string s = "(";
  for (py::ssize_t i = 0; i < a.ndim(); ++i) s += (i ? ", " : "") + std::to_string(a.shape(i));
  return s + (a.ndim() == 1 ? ",)" : ")");
}

/// The faces of `faces_any` (integers of type Index) into `m`, each index
/// checked against the vertex count and reported as given when out of range.
template <class Index>
void add_faces(ember::Mesh& m, const py::array& faces_any, py::ssize_t vertex_count, const std::string& what) {
  const auto f = py::array_t<Index, py::array::c_style | py::array::forcecast>::ensure(faces_any);
  if (!f || f.ndim() != 2 || (f.shape(0) > 0 && f.shape(1) < 3))
    throw ember::Error(what + ": faces must have shape (m, 3) (or (m, k >= 3) polygons), got shape " +
                       shape_of(faces_any));
  const auto fr = f.template unchecked<2>();
  const py::ssize_t k = f.shape(1);
  m.indices.reserve(static_cast<std::size_t>(f.shape(0) * k));
  m.face_offsets.reserve(static_cast<std::size_t>(f.shape(0)) + 1);
  for (py::ssize_t i = 0; i < f.shape(0); ++i) {
    for (py::ssize_t j = 0; j < k; ++j) {
      const Index id = fr(i, j);
      bool negative = false;
      if constexpr (std::is_signed_v<Index>) negative = id < 0;
      if (negative || static_cast<std::uint64_t>(id) >= static_cast<std::uint64_t>(vertex_count))
        throw ember::Error(what + ": face " + std::to_string(i) + " uses vertex index " + std::to_string(id) +
                           ", but there are " + std::to_string(vertex_count) + " vertices");
      m.indices.push_back(static_cast<std::uint32_t>(id));
    }
    m.face_offsets.push_back(static_cast<std::uint32_t>(m.indices.size()));
  }
}

/// A keyword option that must be a bool (or an int used as one).
bool bool_option(py::handle value, const std::string& name) {
  if (!py::isinstance<py::int_>(value))
    throw py::type_error(name + " must be a bool, got " + std::string(py::str(py::type::of(value).attr("__name__"))));
  return PyObject_IsTrue(value.ptr()) == 1;
}

/// A keyword option that must be a whole number in [lo, hi].
int int_option(py::handle value, const std::string& name, long long lo, long long hi, const std::string& range) {
  if (!py::isinstance<py::int_>(value) || py::isinstance<py::bool_>(value))
    throw py::type_error(name + " must be an int (" + range + "), got " +
                         std::string(py::str(py::type::of(value).attr("__name__"))));
  int overflow = 0;
  const long long v = PyLong_AsLongLongAndOverflow(value.ptr(), &overflow);
  if (overflow != 0 || v < lo || v > hi)
    throw py::value_error(name + " must be " + range + ", got " + std::string(py::str(value)));
  return static_cast<int>(v);
}

/// A path given as str, bytes or os.PathLike (pathlib.Path), as a str.
std::string path_arg(py::handle path) { return py::module_::import("os").attr("fsdecode")(path).cast<std::string>(); }

/// One operand from Python: a (vertices, faces) pair or an object with
/// .vertices and .faces. `what` names it in error messages.
ember::Mesh to_mesh(py::handle obj, const std::string& what) {
  py::object vertices, faces;
  if ((py::isinstance<py::tuple>(obj) || py::isinstance<py::list>(obj)) && py::len(obj) == 2) {
    vertices = obj[py::int_(0)];
    faces = obj[py::int_(1)];
  } else if (py::hasattr(obj, "vertices") && py::hasattr(obj, "faces")) {
    vertices = obj.attr("vertices");
    faces = obj.attr("faces");
  } else {
    throw py::type_error(what +
                         ": expected a (vertices, faces) pair or an object with .vertices and .faces "
                         "(e.g. trimesh.Trimesh), got " +
                         std::string(py::str(py::type::of(obj))));
  }
  const auto v = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(vertices);
  if (!v || v.ndim() != 2 || v.shape(1) != 3)
    throw ember::Error(what + ": vertices must be a float array of shape (n, 3)" +
                       (v ? ", got shape " + shape_of(v) : std::string()));
  const py::array f_any = py::array::ensure(faces);
  if (!f_any || (f_any.size() > 0 && f_any.dtype().kind() != 'i' && f_any.dtype().kind() != 'u'))
    throw ember::Error(what + ": faces must be an integer array of shape (m, 3) (or (m, k) polygons)");
  ember::Mesh m;
  const auto vr = v.unchecked<2>();
  m.vertices.resize(static_cast<std::size_t>(v.shape(0)));
  for (py::ssize_t i = 0; i < v.shape(0); ++i) m.vertices[static_cast<std::size_t>(i)] = {vr(i, 0), vr(i, 1), vr(i, 2)};
  // uint64 indices above 2^63 would wrap as int64: read them as they are.
  if (f_any.size() > 0 && f_any.dtype().kind() == 'u' && f_any.dtype().itemsize() == 8)
    add_faces<std::uint64_t>(m, f_any, v.shape(0), what);
  else
    add_faces<std::int64_t>(m, f_any, v.shape(0), what);
  return m;
}

/// (vertices, faces) arrays of a mesh, polygons fan-triangulated; `face_of`
/// gets, per output triangle, the polygon it came from (for provenance).
py::tuple to_arrays(const ember::Mesh& m, std::vector<std::size_t>* face_of = nullptr) {
  py::array_t<double> v({static_cast<py::ssize_t>(m.vertices.size()), py::ssize_t{3}});
  auto vw = v.mutable_unchecked<2>();
  for (std::size_t i = 0; i < m.vertices.size(); ++i) {
    vw(i, 0) = m.vertices[i].x;
    vw(i, 1) = m.vertices[i].y;
    vw(i, 2) = m.vertices[i].z;
  }
  py::array_t<std::int64_t> f({static_cast<py::ssize_t>(m.triangle_count()), py::ssize_t{3}});
  auto fw = f.mutable_unchecked<2>();
  py::ssize_t t = 0;
  for (std::size_t p = 0; p < m.face_count(); ++p) {
    const auto face = m.face(p);
    for (std::size_t i = 1; i + 1 < face.size(); ++i, ++t) {
      fw(t, 0) = face[0];
      fw(t, 1) = face[i];
      fw(t, 2) = face[i + 1];
      if (face_of) face_of->push_back(p);
    }
  }
  return py::make_tuple(v, f);
}

py::dict stats_dict(const ember::BooleanStats& s) {
  py::dict d;
  d["input_triangles"] = s.input_triangles;
  d["dropped_degenerate"] = s.dropped_degenerate;
  d["output_polygons"] = s.output_polygons;
  d["dropped_slivers"] = s.dropped_slivers;
  d["solid_operands"] = s.solid_operands;
  const auto count = [&](const char* name) { return static_cast<std::size_t>(s.diagnostic(name)); };
  d["merged_triangles"] = count("merged_triangles");
  d["solid_path"] = s.diagnostic("solid_path") != 0;
  d["direct_mesh"] = s.diagnostic("direct_mesh") != 0;
  d["output_vertices"] = s.output_vertices;
  d["tjunctions_resolved"] = count("tjunctions_resolved");
  d["collinear_removed"] = count("collinear_removed");
  d["fallback_regions"] = count("fallback_regions");
  d["rounded_degenerate"] = s.rounded_degenerate;
  d["time_ms"] = s.time_ms;
  for (const char* name :
       {"setup_ms", "proof_ms", "solve_ms", "output_ms", "weld_ms", "tjunction_ms", "regions_ms", "triangulate_ms"})
    d[name] = s.diagnostic(name);
  d["threads"] = s.threads;
  return d;
}

/// A result as Python returns it: (vertices, faces[, provenance][, stats]).
py::tuple packed(const ember::BooleanResult& r, bool want_provenance, bool want_stats) {
  std::vector<std::size_t> face_of;
  py::tuple arrays = to_arrays(r.mesh, &face_of);
  py::list out;
  out.append(arrays[0]);
  out.append(arrays[1]);
  if (want_provenance) {
    // Per output triangle: [operand index, face index within that operand].
    py::array_t<std::int64_t> prov({static_cast<py::ssize_t>(face_of.size()), py::ssize_t{2}});
    auto pw = prov.mutable_unchecked<2>();
    for (std::size_t t = 0; t < face_of.size(); ++t) {
      pw(t, 0) = r.provenance[face_of[t]].operand;
      pw(t, 1) = r.provenance[face_of[t]].face;
    }
    out.append(prov);
  }
  if (want_stats) out.append(stats_dict(r.stats));
  return py::tuple(out);
}

/// union/intersection/difference/xor(*meshes, **options), the expression
/// over `meshes` when one is given, or every layer (a list of results) with
/// `layers`; min_k is an option of union alone.
py::object run_boolean(ember::Operation op, const py::tuple& meshes, const py::kwargs& kwargs,
                       const ember::Csg* expression = nullptr, bool layers = false) {
  ember::BooleanOptions options;
  bool want_provenance = false, want_stats = false;
  for (const auto& [key, value] : kwargs) {
    const std::string k = py::str(key);
    if (k == "threads")
      options.threads = int_option(value, k, 0, 1 << 16, "0 (all cores) or a number of threads up to 65536");
    else if (k == "allow_open")
      options.allow_open = bool_option(value, k);
    else if (k == "assume_solid")
      options.all_solid = bool_option(value, k);
    else if (k == "detect_solid")
      options.detect_solid = bool_option(value, k);
    else if (k == "return_provenance")
      want_provenance = bool_option(value, k);
    else if (k == "return_stats")
      want_stats = bool_option(value, k);
    else if (k == "min_k" && op == ember::Operation::Union && !expression && !layers) {
      if (!value.is_none()) {
        op = ember::Operation::AtLeastK;
        const auto n = static_cast<long long>(meshes.size());
        options.min_k =
            int_option(value, k, 1, std::max(n, 1LL), "from 1 to the number of meshes (" + std::to_string(n) + ")");
      }
    } else {
      throw py::type_error("unexpected keyword argument '" + k +
                           "' (options: threads, allow_open, assume_solid, detect_solid, return_provenance, "
                           "return_stats; union also min_k; for expressions use ember.at_least)");
    }
  }
  std::vector<ember::Mesh> operands;
  operands.reserve(meshes.size());
  for (std::size_t i = 0; i < meshes.size(); ++i)
    operands.push_back(to_mesh(meshes[i], "operand " + std::to_string(i)));

  std::vector<ember::BooleanResult> results;
  {
    // The exact core runs on its own threads and touches no Python object.
    py::gil_scoped_release release;
    if (layers)
      results = ember::boolean_layers(operands, options);
    else
      results.push_back(expression ? ember::boolean(operands, *expression, options)
                                   : ember::boolean(operands, op, options));
  }
  // Layers share the input's warnings: warned once.
  std::size_t k = 0;
  for (const ember::BooleanResult& r : results) {
    for (std::size_t w = 0; w < r.warnings.size(); ++w)
      if (k == 0 || w >= results[0].warnings.size() || r.warnings[w] != results[0].warnings[w])
        if (PyErr_WarnEx(PyExc_RuntimeWarning, r.warnings[w].c_str(), 1) != 0) throw py::error_already_set();
    ++k;
  }
  if (!layers) return packed(results[0], want_provenance, want_stats);
  py::list out;
  for (const ember::BooleanResult& r : results) out.append(packed(r, want_provenance, want_stats));
  return out;
}

/// An expression over Python meshes: an ember::Csg over `operands`, which
/// holds each mesh object once (by identity), so a mesh used twice is one
/// operand, converted and quantized once.
struct PyCsg {
  ember::Csg expression;
  std::vector<py::object> operands;
};

/// `e` with operand i renamed to map[i] (rebuilt from its postfix nodes).
ember::Csg renumbered(const ember::Csg& e, const std::vector<std::size_t>& map) {
  using Kind = ember::Csg::Kind;
  std::vector<ember::Csg> stack;
  for (const ember::Csg::Node& node : e.nodes()) {
    if (node.kind == Kind::Operand) {
      stack.push_back(ember::Csg::operand(map[node.value]));
      continue;
    }
    std::vector<ember::Csg> terms(stack.end() - node.arity, stack.end());
    stack.resize(stack.size() - node.arity);
    if (node.kind == Kind::AtLeast) {
      stack.push_back(ember::Csg::at_least(static_cast<int>(node.value), terms));
      continue;
    }
    ember::Csg acc = terms[0];
    for (std::size_t i = 1; i < terms.size(); ++i) {
      switch (node.kind) {
        case Kind::Union: acc = acc | terms[i]; break;
        case Kind::Intersection: acc = acc & terms[i]; break;
        case Kind::Difference: acc = acc - terms[i]; break;
        default: acc = acc ^ terms[i]; break;
      }
    }
    stack.push_back(acc);
  }
  return stack.back();
}

/// `b`'s expression over the operand list `into` (extended by b's meshes not in it).
ember::Csg adopt(const PyCsg& b, std::vector<py::object>& into) {
  std::vector<std::size_t> map(b.operands.size());
  for (std::size_t i = 0; i < b.operands.size(); ++i) {
    std::size_t j = 0;
    while (j < into.size() && !into[j].is(b.operands[i])) ++j;
    if (j == into.size()) into.push_back(b.operands[i]);
    map[i] = j;
  }
  return renumbered(b.expression, map);
}

template <class Combine>
PyCsg combined(const PyCsg& a, const PyCsg& b, Combine&& combine) {
  PyCsg out{a.expression, a.operands};
  const ember::Csg rhs = adopt(b, out.operands);
  out.expression = combine(a.expression, rhs);
  return out;
}

}  // namespace

PYBIND11_MODULE(ember, m) {
  m.doc() = "ember: exact mesh Booleans (EMBER). Meshes are (vertices, faces) numpy pairs or trimesh-like objects.";
  m.attr("__version__") = "0.1.0";
  py::register_exception<ember::Error>(m, "Error", PyExc_ValueError);

  const char* options_doc =
      "(*meshes, threads=0, allow_open=False, assume_solid=False, detect_solid=True, return_provenance=False, "
      "return_stats=False) -> (vertices, faces[, provenance][, stats])\n\n"
      "meshes: (vertices (n,3) float, faces (m,3) int) pairs or objects with .vertices/.faces.\n"
      "Returns float64 (n,3) vertices and int64 (m,3) triangles; provenance (m,2) int64 gives\n"
      "[operand, face] per triangle; stats is a dict. Raises ember.Error on bad input.";
  struct Op {
    const char* name;
    ember::Operation op;
    const char* what;
  };
  for (const Op& o : {Op{"union", ember::Operation::Union, "Inside any mesh (min_k=K: inside at least K meshes). "},
                      Op{"intersection", ember::Operation::Intersection, "Inside every mesh. "},
                      Op{"difference", ember::Operation::Difference, "Inside the first mesh and outside all others. "},
                      Op{"xor", ember::Operation::Xor, "Inside an odd number of meshes. "}}) {
    const ember::Operation op = o.op;
    m.def(
        o.name, [op](const py::args& a, const py::kwargs& k) { return run_boolean(op, a, k); },
        (std::string(o.what) + options_doc).c_str());
  }

  py::class_<PyCsg>(m, "Csg",
                    "A CSG expression over meshes, evaluated as ONE Boolean: Csg(mesh) wraps a mesh "
                    "((vertices, faces) or a trimesh-like object); combine with | & - ^ and ember.at_least; "
                    "evaluate with .evaluate(**options) or ember.evaluate(expr, **options). A mesh object used "
                    "twice is one operand.")
      .def(py::init([](py::object mesh) {
             (void)to_mesh(mesh, "Csg operand");  // fail now, not at evaluation, on a bad mesh
             return PyCsg{ember::Csg::operand(0), {std::move(mesh)}};
           }),
           py::arg("mesh"))
      .def("__or__",
           [](const PyCsg& a, const PyCsg& b) { return combined(a, b, [](auto& x, auto& y) { return x | y; }); })
      .def("__and__",
           [](const PyCsg& a, const PyCsg& b) { return combined(a, b, [](auto& x, auto& y) { return x & y; }); })
      .def("__sub__",
           [](const PyCsg& a, const PyCsg& b) { return combined(a, b, [](auto& x, auto& y) { return x - y; }); })
      .def("__xor__",
           [](const PyCsg& a, const PyCsg& b) { return combined(a, b, [](auto& x, auto& y) { return x ^ y; }); })
      .def_property_readonly(
          "operands", [](const PyCsg& e) { return py::tuple(py::cast(e.operands)); },
          "The distinct meshes, in operand order (#0, #1, ...).")
      .def("__repr__", [](const PyCsg& e) { return "ember.Csg(" + e.expression.to_string() + ")"; })
      .def(
          "evaluate",
          [](const PyCsg& e, const py::kwargs& k) {
            return run_boolean(ember::Operation::Union, py::tuple(py::cast(e.operands)), k, &e.expression);
          },
          "evaluate(threads=0, allow_open=False, assume_solid=False, detect_solid=True, return_provenance=False, "
          "return_stats=False) -> (vertices, faces[, provenance][, stats]): the expression in one Boolean over its "
          "distinct meshes (provenance names them by their index in .operands).");
  m.def(
      "evaluate",
      [](const PyCsg& e, const py::kwargs& k) {
        return run_boolean(ember::Operation::Union, py::tuple(py::cast(e.operands)), k, &e.expression);
      },
      py::arg("expression"), "evaluate(expression, **options): the same as expression.evaluate(**options).");
  m.def(
      "layers",
      [](const py::args& a, const py::kwargs& k) { return run_boolean(ember::Operation::Union, a, k, nullptr, true); },
      "layers(*meshes, threads=0, allow_open=False, assume_solid=False, detect_solid=True, return_provenance=False, "
      "return_stats=False) -> [layer 1, ..., layer n]: every layer from one pass; layer k (a (vertices, faces[, ...]) "
      "tuple as union returns) is the solid inside at least k meshes.");
  m.def(
      "at_least",
      [](const py::args& terms) {
        if (terms.size() < 2) throw py::type_error("at_least(k, *terms) needs k and at least one term");
        const int k = int_option(terms[0], "k", 1, static_cast<long long>(terms.size() - 1),
                                 "from 1 to the number of terms (" + std::to_string(terms.size() - 1) + ")");
        PyCsg out;
        std::vector<ember::Csg> parts;
        for (std::size_t i = 1; i < terms.size(); ++i) {
          const PyCsg t = py::isinstance<PyCsg>(terms[i])
                              ? terms[i].cast<PyCsg>()
                              : PyCsg{ember::Csg::operand(0), {py::reinterpret_borrow<py::object>(terms[i])}};
          parts.push_back(adopt(t, out.operands));
        }
        out.expression = ember::Csg::at_least(k, parts);
        return out;
      },
      "at_least(k, *terms) -> Csg: inside at least k of the terms (Csg expressions or meshes).");

  m.def(
      "read",
      [](py::handle path_like) {
        const std::string path = path_arg(path_like);
        ember::Mesh mesh;
        {
          py::gil_scoped_release release;
          mesh = ember::read_mesh(path);
        }
        return to_arrays(mesh);
      },
      py::arg("path"),
      "read(path) -> (vertices, faces): one mesh; the format follows the extension "
      "(.obj .stl .off .ply .3mf). Polygons are fan-triangulated.");
  m.def(
      "read_all",
      [](py::handle path_like) {
        const std::string path = path_arg(path_like);
        std::vector<ember::Mesh> meshes;
        {
          py::gil_scoped_release release;
          meshes = ember::read_meshes(path);
        }
        py::list out;
        for (const ember::Mesh& mesh : meshes) out.append(to_arrays(mesh));
        return out;
      },
      py::arg("path"), "read_all(path) -> [(vertices, faces), ...]: every object of a 3MF file (one per build item).");
  m.def(
      "write",
      [](py::handle path_like, py::handle mesh, py::object provenance) {
        const std::string path = path_arg(path_like);
        const ember::Mesh m = to_mesh(mesh, "mesh");
        std::vector<ember::Provenance> sources;
        if (!provenance.is_none()) {
          const auto a = py::array_t<std::int64_t, py::array::c_style | py::array::forcecast>::ensure(provenance);
          if (!a || a.ndim() != 2 || a.shape(1) != 2)
            throw ember::Error("write: provenance must be an (m, 2) integer array [operand, face] per face");
          auto r = a.unchecked<2>();
          for (py::ssize_t i = 0; i < r.shape(0); ++i) {
            if (r(i, 0) < 0 || r(i, 1) < 0 || r(i, 0) > UINT32_MAX || r(i, 1) > UINT32_MAX)
              throw ember::Error("write: provenance row " + std::to_string(i) + " is out of range");
            sources.push_back({static_cast<std::uint32_t>(r(i, 0)), static_cast<std::uint32_t>(r(i, 1))});
          }
        }
        py::gil_scoped_release release;
        ember::write_mesh(m, path, sources);
      },
      py::arg("path"), py::arg("mesh"), py::arg("provenance") = py::none(),
      "write(path, mesh, provenance=None): writes a (vertices, faces) pair or trimesh-like object; the format follows "
      "the extension. provenance ((m, 2) [operand, face] per face, as returned by return_provenance=True) is stored "
      "as PLY face properties operand and source_face; other formats leave it out.");
}
