// CGAL peer of the comparison benchmark; driven by bench/compare/bench.py.
//
//   cgal_runner A.bin B.bin [--ops ..] [--runs R] [--budget-ms B] [--no-checks]
//
// Times CGAL::Polygon_mesh_processing::corefine_and_compute_{union,intersection,
// difference} with the Epick kernel on CGAL::Surface_mesh. The timed region
// INCLUDES building both Surface_mesh from the flat arrays (corefinement
// modifies its inputs, so they are rebuilt for every run) and copying the
// result back into flat arrays. CGAL is single-threaded here.
//
// Untimed input validation first (unless --no-checks): both meshes must load as
// a closed, manifold triangle mesh without self-intersections (CGAL's documented
// preconditions); otherwise every operation is reported as failed with the reason.
// A `false` from corefine_and_compute_* (output would not be manifold) and any
// exception are recorded as failures too.
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/corefinement.h>
#include <CGAL/Polygon_mesh_processing/self_intersections.h>
#include <CGAL/Surface_mesh.h>

#include <cstdio>
#include <string>

#include "runner_common.hpp"

namespace {

using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using SM = CGAL::Surface_mesh<K::Point_3>;
namespace PMP = CGAL::Polygon_mesh_processing;

// Returns false when a face could not be added (non-manifold input).
bool build(const bench::TriMesh& t, SM& m) {
  m.reserve(static_cast<SM::size_type>(t.vertex_count()), static_cast<SM::size_type>(3 * t.triangle_count() / 2),
            static_cast<SM::size_type>(t.triangle_count()));
  for (std::size_t i = 0; i < t.vertex_count(); ++i)
    m.add_vertex(K::Point_3(t.xyz[3 * i], t.xyz[3 * i + 1], t.xyz[3 * i + 2]));
  bool ok = true;
  for (std::size_t f = 0; f < t.triangle_count(); ++f) {
    auto r = m.add_face(SM::Vertex_index(t.tri[3 * f]), SM::Vertex_index(t.tri[3 * f + 1]),
                        SM::Vertex_index(t.tri[3 * f + 2]));
    if (r == SM::null_face()) ok = false;
  }
  return ok;
}

void extract(SM& m, bench::TriMesh& out) {
  if (m.has_garbage()) m.collect_garbage();
  out.xyz.resize(3 * m.number_of_vertices());
  std::size_t i = 0;
  for (auto v : m.vertices()) {
    const auto& p = m.point(v);
    out.xyz[i++] = p.x();
    out.xyz[i++] = p.y();
    out.xyz[i++] = p.z();
  }
  out.tri.clear();
  out.tri.reserve(3 * m.number_of_faces());
  for (auto f : m.faces())
    for (auto v : m.vertices_around_face(m.halfedge(f))) out.tri.push_back(static_cast<std::uint32_t>(v.idx()));
}

std::string validate(const bench::TriMesh& t, const char* name) {
  SM m;
  if (!build(t, m)) return std::string("input ") + name + " rejected: not manifold (add_face failed)";
  if (!CGAL::is_closed(m)) return std::string("input ") + name + " rejected: not closed";
  if (PMP::does_self_intersect(m)) return std::string("input ") + name + " rejected: self-intersections";
  return "";
}

}  // namespace

int main(int argc, char** argv) {
  try {
    bool checks = true;
    std::vector<char*> rest;
    for (int i = 0; i < argc; ++i) {
      if (std::string(argv[i]) == "--no-checks")
        checks = false;
      else
        rest.push_back(argv[i]);
    }
    bench::RunnerArgs args = bench::parse_runner_args(static_cast<int>(rest.size()), rest.data(), 1);
    args.threads = 1;
    const bench::TriMesh a = bench::read_bin(args.a), b = bench::read_bin(args.b);
    const std::size_t in_tris = a.triangle_count() + b.triangle_count();
    std::string rejected;
    if (checks) {
      rejected = validate(a, "A");
      if (rejected.empty()) rejected = validate(b, "B");
    }
    for (const std::string& op : args.ops) {
      bench::TriMesh last;
      bench::time_op(
          "cgal", args, op, in_tris,
          [&](bench::OpOutput& o) {
            if (!rejected.empty()) {
              o.ok = false;
              o.error = rejected;
              return;
            }
            SM ma, mb, out;
            build(a, ma);
            build(b, mb);
            bool ok = op == "union"          ? PMP::corefine_and_compute_union(ma, mb, out)
                      : op == "intersection" ? PMP::corefine_and_compute_intersection(ma, mb, out)
                      : op == "difference"   ? PMP::corefine_and_compute_difference(ma, mb, out)
                                             : throw std::runtime_error("unknown op " + op);
            if (!ok) {
              o.ok = false;
              o.error = "corefine_and_compute returned false (output not manifold)";
              return;
            }
            extract(out, last);
          },
          [&](bench::OpOutput& o) {
            o.volume = bench::signed_volume(last.xyz, last.tri);
            o.polygons = last.triangle_count();
          });
    }
    return 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "cgal_runner: %s\n", e.what());
    return 1;
  }
}
