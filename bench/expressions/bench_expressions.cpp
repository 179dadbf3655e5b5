// Expressions in one pass against the same expression as a chain of binary
// Booleans through ember (each intermediate result, rounded to double, is
// the next step's operand), on four overlapping meshes. Prints one line per
// expression: the median time of each, their ratio, and the volumes.
//
//   bench_expressions [--threads N] [--repeats R] [--write DIR] [A B C D ...]
//
// Then all layers of the operands (inside at least k, k = 1..n) from one
// boolean_layers call against n separate AtLeastK Booleans. --write DIR
// writes the placed operands as DIR/op0.obj .. so that peers can run the
// same chains (bench/expressions/run.py).
//
// Without files it uses four procedural solids. Files are read as given and
// moved so that they overlap as in the paper (each scaled into the unit box,
// D..B offset by a fraction of it, and rotated). Timings are Boolean time only
// (arrays to arrays), not file I/O.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <string>
#include <vector>

#include "ember/boolean.hpp"
#include "ember/csg.hpp"
#include "ember/error.hpp"
#include "ember/io/mesh_io.hpp"
#include "ember/shapes.hpp"

namespace {

using ember::Csg;
using ember::Mesh;
using ember::Operation;

/// Scales `m` into [-0.5, 0.5]^3 (uniformly), rotates it about z and x by
/// `angle` and moves it by `offset`.
Mesh placed(Mesh m, double angle, ember::Vec3d offset) {
  ember::Vec3d lo{1e300, 1e300, 1e300}, hi{-1e300, -1e300, -1e300};
  for (const ember::Vec3d& p : m.vertices) {
    lo = {std::min(lo.x, p.x), std::min(lo.y, p.y), std::min(lo.z, p.z)};
    hi = {std::max(hi.x, p.x), std::max(hi.y, p.y), std::max(hi.z, p.z)};
  }
  const double s = 1.0 / std::max({hi.x - lo.x, hi.y - lo.y, hi.z - lo.z});
  const double c = std::cos(angle), n = std::sin(angle);
  for (ember::Vec3d& p : m.vertices) {
    const ember::Vec3d q{(p.x - (lo.x + hi.x) / 2) * s, (p.y - (lo.y + hi.y) / 2) * s, (p.z - (lo.z + hi.z) / 2) * s};
    const ember::Vec3d r{c * q.x - n * q.y, n * q.x + c * q.y, q.z};
    p = {r.x + offset.x, c * r.y - n * r.z + offset.y, n * r.y + c * r.z + offset.z};
  }
  return m;
}

double volume(const Mesh& m) {
  double six = 0;
  for (std::size_t f = 0; f < m.face_count(); ++f) {
    const auto face = m.face(f);
    const ember::Vec3d a = m.vertices[face[0]];
    for (std::size_t i = 1; i + 1 < face.size(); ++i) {
      const ember::Vec3d b = m.vertices[face[i]], c = m.vertices[face[i + 1]];
      six += a.x * (b.y * c.z - b.z * c.y) - a.y * (b.x * c.z - b.z * c.x) + a.z * (b.x * c.y - b.y * c.x);
    }
  }
  return six / 6;
}

/// Median wall time of `repeats` runs of f, in milliseconds; `out` keeps the last result.
double median_ms(int repeats, const std::function<Mesh()>& f, Mesh& out) {
  std::vector<double> t;
  for (int i = 0; i < repeats; ++i) {
    const auto start = std::chrono::steady_clock::now();
    out = f();
    t.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count());
  }
  std::sort(t.begin(), t.end());
  return t[t.size() / 2];
}

struct Step {
  Operation op;
  std::vector<int> operands;  ///< indices into the inputs; -1 is the previous step's result
};

struct Case {
  const char* name;
  Csg expression;
  std::vector<Step> chain;  ///< the same expression as binary Booleans
};

}  // namespace

int main(int argc, char** argv) {
  try {
    ember::BooleanOptions options;
    options.threads = 2;
    int repeats = 5;
    std::vector<std::string> files;
    for (int i = 1; i < argc; ++i) {
      const std::string a = argv[i];
      if (a == "--threads" && i + 1 < argc)
        options.threads = std::atoi(argv[++i]);
      else if (a == "--repeats" && i + 1 < argc)
        repeats = std::max(1, std::atoi(argv[++i]));
      else
        files.push_back(a);
    }
    std::string write_dir;
    for (std::size_t i = 0; i + 1 < files.size(); ++i)
      if (files[i] == "--write") {
        write_dir = files[i + 1];
        files.erase(files.begin() + static_cast<std::ptrdiff_t>(i), files.begin() + static_cast<std::ptrdiff_t>(i) + 2);
        break;
      }
    if (!files.empty() && files.size() < 4) throw ember::Error("give four or more mesh files, or none");
    std::vector<Mesh> in;
    if (files.empty()) {
      in = {ember::shapes::uv_sphere({0, 0, 0}, 1.0, 128, 64), ember::shapes::torus(1.0, 0.35, 192, 96),
            ember::shapes::uv_sphere({0.9, 0, 0.2}, 0.6, 96, 48), ember::shapes::torus(0.8, 0.3, 160, 80)};
    } else {
      for (const std::string& f : files) in.push_back(ember::read_mesh(f));
    }
    // Each operand turned and moved by a fraction of its size, so all overlap.
    for (std::size_t i = 0; i < in.size(); ++i) {
      const double t = static_cast<double>(i);
      in[i] = placed(std::move(in[i]), 0.7 * t,
                     {0.2 * std::sin(2.1 * t), 0.2 * std::cos(1.3 * t) - 0.2, 0.1 * std::sin(t)});
    }
    if (!write_dir.empty())
      for (std::size_t i = 0; i < in.size(); ++i)
        ember::write_mesh(in[i], write_dir + "/op" + std::to_string(i) + ".obj");
    std::size_t triangles = 0;
    for (const Mesh& m : in) triangles += m.triangle_count();

    const Csg a = Csg::operand(0), b = Csg::operand(1), c = Csg::operand(2), d = Csg::operand(3);
    const std::vector<Case> cases = {
        {"((A|B)-C)&D",
         ((a | b) - c) & d,
         {{Operation::Union, {0, 1}}, {Operation::Difference, {-1, 2}}, {Operation::Intersection, {-1, 3}}}},
        {"(A^B)|(C-D)", (a ^ b) | (c - d), {}},  // two branches: chained below
        {"A-B-C-D",
         a - b - c - d,
         {{Operation::Difference, {0, 1}}, {Operation::Difference, {-1, 2}}, {Operation::Difference, {-1, 3}}}},
    };
    const std::vector<Mesh> four(in.begin(), in.begin() + 4);
    std::printf("expressions over the first four operands, %zu triangles in all, %d threads, median of %d runs\n",
                triangles, options.threads, repeats);
    std::printf("%-14s %12s %12s %8s %14s %14s\n", "expression", "one pass ms", "chain ms", "speedup", "volume 1-pass",
                "volume chain");
    for (const Case& k : cases) {
      Mesh one, chained;
      const double t_one = median_ms(
          repeats, [&] { return ember::boolean(four, k.expression, options).mesh; }, one);
      const double t_chain = median_ms(
          repeats,
          [&] {
            if (k.chain.empty()) {  // (A^B)|(C-D): two binary Booleans, then their union
              const Mesh x = ember::boolean({in[0], in[1]}, Operation::Xor, options).mesh;
              const Mesh y = ember::boolean({in[2], in[3]}, Operation::Difference, options).mesh;
              return ember::boolean({x, y}, Operation::Union, options).mesh;
            }
            Mesh previous;
            for (const Step& s : k.chain) {
              std::vector<Mesh> ops;
              for (const int o : s.operands) ops.push_back(o < 0 ? previous : in[o]);
              previous = ember::boolean(ops, s.op, options).mesh;
            }
            return previous;
          },
          chained);
      std::printf("%-14s %12.1f %12.1f %7.2fx %14.6f %14.6f\n", k.name, t_one, t_chain, t_chain / t_one, volume(one),
                  volume(chained));
    }
    // All layers: one pass against one AtLeastK Boolean per k.
    std::vector<double> layer_volumes;
    Mesh unused;
    const double t_layers = median_ms(
        repeats,
        [&] {
          layer_volumes.clear();
          for (const ember::BooleanResult& r : ember::boolean_layers(in, options))
            layer_volumes.push_back(volume(r.mesh));
          return Mesh{};
        },
        unused);
    double t_separate = 0;
    bool same = true;
    for (std::size_t k = 1; k <= in.size(); ++k) {
      ember::BooleanOptions at_least = options;
      at_least.min_k = static_cast<int>(k);
      Mesh layer;
      t_separate += median_ms(
          repeats, [&] { return ember::boolean(in, Operation::AtLeastK, at_least).mesh; }, layer);
      same &= std::abs(volume(layer) - layer_volumes[k - 1]) <= 1e-9 * std::abs(volume(layer)) + 1e-15;
    }
    std::printf("%-14s %12.1f %12.1f %7.2fx   (%zu layers; volumes %s)\n", "layers", t_layers, t_separate,
                t_separate / t_layers, in.size(), same ? "agree" : "DIFFER");
    return same ? 0 : 1;
  } catch (const ember::Error& e) {
    std::fprintf(stderr, "bench_expressions: %s\n", e.what());
    return 1;
  }
}
