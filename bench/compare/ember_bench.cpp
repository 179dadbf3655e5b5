// ember side of the comparison benchmark; driven by bench/compare/bench.py.
//
//   ember_bench prepare IN OUT.bin [--normalize] [--subdivide K] [--matrix m0,..,m15]
//       Reads any mesh ember reads (OBJ/STL/OFF/PLY), fan-triangulates it,
//       optionally midpoint-subdivides it K times (1 -> 4 triangles, shape
//       preserving), optionally normalizes it (bounding-box center to the
//       origin, largest extent 1), applies the column-major 4x4 matrix
//       (p' = M * (p, 1)), rounds every coordinate to float32 (so that all
//       tools, Manifold included, get bit-identical input) and writes the
//       benchmark's binary format (meshbin.hpp). Prints {"triangles":..,"vertices":..}.
//
//   ember_bench run A.bin B.bin [--ops ..] [--runs R] [--budget-ms B] [--threads T] [--warmup W]
//                   [--solid] [--no-detect]
//       Times ember::boolean in-process: building the two ember::Mesh from the
//       flat arrays + the Boolean (its output is already flat arrays). One JSON
//       line per operation (runner_common.hpp), with the median of each phase
//       of BooleanStats::diagnostics (setup_ms, proof_ms, solve_ms, output_ms).
#include <algorithm>
#include <array>
#include <cstdio>
#include <map>
#include <sstream>
#include <string>
#include <span>
#include <utility>
#include <vector>

#include "ember/boolean.hpp"
#include "ember/io/mesh_io.hpp"
#include "ember/process.hpp"
#include "runner_common.hpp"

namespace {

bench::TriMesh triangulate(const ember::Mesh& m) {
  bench::TriMesh t;
  t.xyz.reserve(3 * m.vertices.size());
  for (const auto& v : m.vertices) t.xyz.insert(t.xyz.end(), {v.x, v.y, v.z});
  for (std::size_t f = 0; f < m.face_count(); ++f) {
    auto face = m.face(f);
    for (std::size_t i = 1; i + 1 < face.size(); ++i) t.tri.insert(t.tri.end(), {face[0], face[i], face[i + 1]});
  }
  return t;
}

bench::TriMesh subdivide(const bench::TriMesh& m) {
  bench::TriMesh o;
  o.xyz = m.xyz;
  std::map<std::pair<std::uint32_t, std::uint32_t>, std::uint32_t> mid;
  auto midpoint = [&](std::uint32_t a, std::uint32_t b) {
    auto key = std::minmax(a, b);
    auto it = mid.find(key);
    if (it != mid.end()) return it->second;
    auto id = static_cast<std::uint32_t>(o.xyz.size() / 3);
    for (int k = 0; k < 3; ++k) o.xyz.push_back(0.5 * (m.xyz[3 * a + k] + m.xyz[3 * b + k]));
    mid.emplace(key, id);
    return id;
  };
  for (std::size_t t = 0; t < m.triangle_count(); ++t) {
    std::uint32_t a = m.tri[3 * t], b = m.tri[3 * t + 1], c = m.tri[3 * t + 2];
    std::uint32_t ab = midpoint(a, b), bc = midpoint(b, c), ca = midpoint(c, a);
    o.tri.insert(o.tri.end(), {a, ab, ca, ab, b, bc, ca, bc, c, ab, bc, ca});
  }
  return o;
}

int prepare(int argc, char** argv) {
  if (argc < 4)
    throw std::runtime_error("usage: ember_bench prepare IN OUT [--normalize] [--subdivide K] [--matrix ..]");
  std::string in = argv[2], out = argv[3];
  bool normalize = false;
  int subdiv = 0;
  std::array<double, 16> M{1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};
  for (int i = 4; i < argc; ++i) {
    std::string s = argv[i];
    if (s == "--normalize") {
      normalize = true;
    } else if (s == "--subdivide" && i + 1 < argc) {
      subdiv = std::stoi(argv[++i]);
    } else if (s == "--matrix" && i + 1 < argc) {
      std::stringstream ss(argv[++i]);
      std::string v;
      for (int k = 0; k < 16; ++k) {
        if (!std::getline(ss, v, ',')) throw std::runtime_error("--matrix needs 16 comma-separated values");
        M[k] = std::stod(v);
      }
    } else {
      throw std::runtime_error("unknown argument " + s);
    }
  }
  bench::TriMesh m = triangulate(ember::read_mesh(in));
  for (int k = 0; k < subdiv; ++k) m = subdivide(m);
  if (normalize && !m.xyz.empty()) {
    double lo[3], hi[3];
    for (int k = 0; k < 3; ++k) lo[k] = hi[k] = m.xyz[k];
    for (std::size_t i = 0; i < m.xyz.size(); ++i) {
      lo[i % 3] = std::min(lo[i % 3], m.xyz[i]);
      hi[i % 3] = std::max(hi[i % 3], m.xyz[i]);
    }
    double ext = std::max({hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]});
    double s = ext > 0 ? 1.0 / ext : 1.0;
    for (std::size_t i = 0; i < m.xyz.size(); ++i) m.xyz[i] = (m.xyz[i] - 0.5 * (lo[i % 3] + hi[i % 3])) * s;
  }
  for (std::size_t v = 0; v < m.vertex_count(); ++v) {
    double x = m.xyz[3 * v], y = m.xyz[3 * v + 1], z = m.xyz[3 * v + 2];
    for (int r = 0; r < 3; ++r)
      m.xyz[3 * v + r] = static_cast<float>(M[r] * x + M[4 + r] * y + M[8 + r] * z + M[12 + r]);
  }
  bench::write_bin(m, out);
  std::printf("{\"triangles\":%zu,\"vertices\":%zu}\n", m.triangle_count(), m.vertex_count());
  return 0;
}

/// The median of each phase of the timed runs, as JSON members
/// (,"setup_ms":..,"proof_ms":..,"solve_ms":..,"output_ms":.., then the
/// output stage's steps "weld_ms", "tjunction_ms", "regions_ms", "triangulate_ms").
std::string phase_medians(std::span<const ember::BooleanStats> runs) {
  const auto median = [&](const char* name) {
    std::vector<double> v;
    for (const ember::BooleanStats& s : runs) v.push_back(s.diagnostic(name));
    return bench::median_of(std::move(v));
  };
  std::string out;
  for (const char* name :
       {"setup_ms", "proof_ms", "solve_ms", "output_ms", "weld_ms", "tjunction_ms", "regions_ms", "triangulate_ms"})
    out += std::string(",\"") + name + "\":" + bench::json_number(median(name));
  return out;
}

ember::Mesh to_ember(const bench::TriMesh& t) {
  ember::Mesh m;
  const std::size_t nv = t.vertex_count(), nt = t.triangle_count();
  m.vertices.resize(nv);
  for (std::size_t i = 0; i < nv; ++i) m.vertices[i] = {t.xyz[3 * i], t.xyz[3 * i + 1], t.xyz[3 * i + 2]};
  m.indices = t.tri;
  m.face_offsets.resize(nt + 1);
  for (std::size_t f = 0; f <= nt; ++f) m.face_offsets[f] = static_cast<std::uint32_t>(3 * f);
  return m;
}

int run(int argc, char** argv) {
  bench::RunnerArgs args = bench::parse_runner_args(argc, argv, 2);
  const bench::TriMesh a = bench::read_bin(args.a), b = bench::read_bin(args.b);
  const std::size_t in_tris = a.triangle_count() + b.triangle_count();
  for (const std::string& op : args.ops) {
    ember::Operation o = op == "union"          ? ember::Operation::Union
                         : op == "intersection" ? ember::Operation::Intersection
                         : op == "difference"   ? ember::Operation::Difference
                                                : throw std::runtime_error("unknown op " + op);
    ember::BooleanOptions opt;
    opt.threads = args.threads;
    opt.all_solid = args.solid;
    opt.detect_solid = !args.no_detect;
    ember::BooleanResult last;
    std::vector<ember::BooleanStats> stats;  // every run's, warm-up runs first
    bench::time_op(
        "ember", args, op, in_tris,
        [&](bench::OpOutput&) {
          std::array<ember::Mesh, 2> operands{to_ember(a), to_ember(b)};
          last = ember::boolean(std::span<const ember::Mesh>(operands), o, opt);
          stats.push_back(last.stats);
        },
        [&](bench::OpOutput& out) {
          const ember::Mesh& m = last.mesh;
          bench::TriMesh t = triangulate(m);
          out.volume = bench::signed_volume(t.xyz, t.tri);
          out.polygons = m.face_count();
          if (!last.warnings.empty()) out.error = "warning: " + last.warnings.front();
        },
        [&] { return phase_medians(std::span(stats).subspan(std::min<std::size_t>(args.warmup, stats.size()))); });
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  // As the ember CLI does (ember/process.hpp): without it, glibc's per-thread
  // heaps keep what the workers free, and peak RSS grows with the thread
  // count and the repeated runs (docs/benchmark.md, the `_rss_mib` column).
  ember::cap_malloc_arenas();
  try {
    std::string mode = argc > 1 ? argv[1] : "";
    if (mode == "prepare") return prepare(argc, argv);
    if (mode == "run") return run(argc, argv);
    std::fprintf(stderr, "usage: ember_bench prepare|run ... (see docs/benchmark.md)\n");
    return 2;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "ember_bench: %s\n", e.what());
    return 1;
  }
}
