// The `ember` command line: exact mesh Booleans on files.
//
//   ember union|intersection|difference|xor A B [C ...] -o OUT
//         [--min-k K] [--threads N] [--stats] [--allow-open] [--assume-solid] [--no-solid-check] [--quiet] [--polygons]
//   ember union A B [C ...] --layers -o L.obj   (L-1.obj .. L-N.obj: inside at least k inputs)
//   ember eval '(A | B) - C' -o OUT [the same options but --min-k and --layers]
//   ember demo [-o DIR] [--threads N]
//   ember --version
//
// Formats follow the file extension (.obj .stl .ply .off .3mf .gltf .glb). Errors print one
// line on stderr and exit with 1 (2 for usage errors); no partial output file
// is ever left behind (results are written to a temporary name and renamed).
#include <CLI/CLI.hpp>

#include <charconv>
#include <cstdio>
#include <filesystem>
#include <new>
#include <optional>
#include <string>
#include <vector>

#include "ember/boolean.hpp"
#include "ember/csg.hpp"
#include "ember/error.hpp"
#include "ember/io/mesh_io.hpp"
#include "ember/process.hpp"
#include "ember/shapes.hpp"
#include "cli/expression.hpp"
#include "cli/operands.hpp"
#include "cli/progress.hpp"
#include "cli/output_file.hpp"
#include "cli/stats.hpp"
#include "cli/usage.hpp"

namespace fs = std::filesystem;

namespace {

constexpr const char* kThreadsRange = "0 (all cores) or a number of threads up to 65536";

const char* operation_name(ember::Operation op) {
  switch (op) {
    case ember::Operation::Union: return "union";
    case ember::Operation::Intersection: return "intersection";
    case ember::Operation::Difference: return "difference";
    case ember::Operation::Xor: return "xor";
    case ember::Operation::AtLeastK: return "at-least-k";
  }
  return "?";
}

/// What the command is doing, for the message when memory runs out.
std::string g_activity;

/// Writes a mesh in the format of out's extension (atomically, privately).
void write_atomically(const ember::Mesh& mesh, const fs::path& out,
                      std::span<const ember::Provenance> provenance = {}) {
  g_activity = "writing " + out.string();
  ember::cli::write_file_atomically(ember::write_mesh(mesh, ember::format_from_path(out), provenance), out);
}

/// The library names inputs "operand i"; the user knows them by file name.
/// Replaces a leading "operand i" (the whole number) with the i-th path.
std::string name_operand(const std::string& msg, const std::vector<std::string>& inputs) {
  const std::string key = "operand ";
  if (msg.rfind(key, 0) != 0) return msg;
  std::size_t index = 0;
  const char* begin = msg.data() + key.size();
  const auto [end, ec] = std::from_chars(begin, msg.data() + msg.size(), index);
  if (ec != std::errc{} || index >= inputs.size()) return msg;
  return inputs[index] + msg.substr(static_cast<std::size_t>(end - msg.data()));
}

struct BooleanArgs {
  std::vector<std::string> inputs;
  std::string output;
  std::string min_k;  ///< as given (checked after parsing: usage.hpp)
  std::string threads = "0";
  std::string max_3mf_triangles;   ///< as given; empty: ReadOptions' default
  std::string max_3mf_instancing;  ///< as given; empty: ReadOptions' default
  bool stats = false;
  bool allow_open = false;
  bool assume_solid = false;
  bool no_solid_check = false;
  bool polygons = false;
  bool quiet = false;
  bool layers = false;  ///< union --layers: every "at least k" layer, one file each
};

/// Options from the command line; usage errors (exit 2) name the option and
/// range. `operands` is the number of operands (a 3MF file may hold several),
/// or, before the files are read, the number of files (a lower bound).
ember::BooleanOptions boolean_options(ember::Operation& op, const BooleanArgs& a, std::size_t operands) {
  ember::BooleanOptions options;
  options.threads = ember::cli::parse_int_option("--threads", a.threads, 0, 1 << 16, kThreadsRange);
  options.allow_open = a.allow_open;
  options.all_solid = a.assume_solid;
  options.detect_solid = !a.no_solid_check;
  if (a.polygons) options.output = ember::BooleanOptions::Output::Polygons;
  if (a.layers && op != ember::Operation::Union)
    throw ember::cli::UsageError("--layers applies to 'union' only (every layer: inside at least k inputs)");
  if (a.layers && !a.min_k.empty())
    throw ember::cli::UsageError("--layers writes every k; it cannot be combined with --min-k");
  if (a.min_k.empty()) return options;
  const int n = static_cast<int>(operands);
  const std::string range = "K from 1 to the number of operands (" + std::to_string(n) + ")";
  if (op != ember::Operation::Union)
    throw ember::cli::UsageError("--min-k applies to 'union' only (the solid inside at least K inputs); " + range);
  options.min_k = ember::cli::parse_int_option("--min-k", a.min_k, 1, n, range);
  op = ember::Operation::AtLeastK;
  return options;
}

/// Each object of a 3MF file is an operand, so a file count below 2 or a
/// --min-k above the file count is only known to be wrong once 3MF files
/// are read.
bool has_3mf_input(const BooleanArgs& a) {
  for (const std::string& in : a.inputs) {
    try {
      if (ember::format_from_path(in) == ember::MeshFormat::ThreeMf) return true;
    } catch (const ember::Error&) {
      // An unknown extension: reported when the file is read, after the usage checks.
    }
  }
  return false;
}

void check_operand_count(std::size_t n, const BooleanArgs& a) {
  if (n >= 2) return;
  throw ember::cli::UsageError("at least 2 operands are required, but " +
                               (a.inputs.empty() ? std::string("none were") : "'" + a.inputs[0] + "' holds 1") +
                               " (each input file is one operand, each object of a 3MF file one)");
}

ember::ReadOptions read_options_of(const BooleanArgs& a) {
  ember::ReadOptions read_options;
  if (!a.max_3mf_triangles.empty())
    read_options.max_3mf_triangles =
        ember::cli::parse_count_option("--max-3mf-triangles", a.max_3mf_triangles, "a whole number from 1");
  if (!a.max_3mf_instancing.empty())
    read_options.max_3mf_instancing =
        ember::cli::parse_count_option("--max-3mf-instancing", a.max_3mf_instancing, "a whole number from 1");
  return read_options;
}

/// The common part of every Boolean command once its operands are read:
/// runs `compute` (with a progress bar on a terminal), prints the warnings,
/// writes the output and the stats. Errors about an operand name its file.
template <class Compute>
int compute_and_write(const ember::cli::Operands& operands, const std::vector<std::string>& read_warnings,
                      ember::BooleanOptions options, const BooleanArgs& a, const std::string& label, Compute&& compute);

int run_boolean(ember::Operation op, const BooleanArgs& a) {
  const bool any_3mf = has_3mf_input(a);
  // Usage errors before any file is read, as far as they are known then.
  if (any_3mf) {
    BooleanArgs without_k = a;
    without_k.min_k.clear();
    ember::Operation early = op;
    (void)boolean_options(early, without_k, 0);
    if (!a.min_k.empty() && op != ember::Operation::Union)
      (void)boolean_options(early, a, 0);  // the "union only" error
  } else {
    check_operand_count(a.inputs.size(), a);
    ember::Operation early = op;
    (void)boolean_options(early, a, a.inputs.size());
  }
  ember::format_from_path(a.output);  // reject an unknown output extension before any work
  std::vector<std::string> read_warnings;
  const ember::cli::Operands operands =
      ember::cli::read_operands(a.inputs, &read_warnings, &g_activity, read_options_of(a));
  check_operand_count(operands.meshes.size(), a);
  const ember::BooleanOptions options = boolean_options(op, a, operands.meshes.size());
  return compute_and_write(operands, read_warnings, options, a, operation_name(op),
                           [&](const ember::BooleanOptions& o) {
                             if (a.layers) return ember::boolean_layers(operands.meshes, o);
                             return std::vector<ember::BooleanResult>{ember::boolean(operands.meshes, op, o)};
                           });
}

template <class Compute>
int compute_and_write(const ember::cli::Operands& operands, const std::vector<std::string>& read_warnings,
                      ember::BooleanOptions options, const BooleanArgs& a, const std::string& label,
                      Compute&& compute) {
  std::size_t triangles = 0;
  for (const ember::Mesh& m : operands.meshes) triangles += m.triangle_count();
  g_activity = "computing the Boolean of " + std::to_string(triangles) + " triangles";
  if (!a.quiet)
    for (const std::string& w : read_warnings) std::fprintf(stderr, "ember: warning: %s\n", w.c_str());
  std::vector<ember::BooleanResult> results;
  try {
    // Destroyed (bar erased) before any warning or error is printed.
    const auto progress = ember::cli::ProgressDisplay::on_terminal(!a.quiet);
    if (progress) options.progress = progress->callback();
    results = compute(options);
  } catch (const ember::Error& e) {
    const std::optional<std::size_t> o = e.operand();
    if (o && *o < operands.names.size()) throw ember::Error(e.problem(), {.file = operands.names[*o]});
    throw;
  }
  // One output, or with --layers one per layer: OUT's name with -k before the extension.
  std::vector<fs::path> outputs;
  for (std::size_t k = 1; k <= results.size(); ++k) {
    const fs::path out(a.output);
    outputs.push_back(a.layers ? out.parent_path() /
                                     (out.stem().string() + "-" + std::to_string(k) + out.extension().string())
                               : out);
  }
  if (!a.quiet) {
    // Layers share the input's warnings (they come first in each): printed once.
    std::size_t shared = results[0].warnings.size();
    for (const ember::BooleanResult& r : results) {
      std::size_t n = 0;
      while (n < shared && n < r.warnings.size() && r.warnings[n] == results[0].warnings[n]) ++n;
      shared = n;
    }
    for (std::size_t i = 0; i < shared; ++i)
      std::fprintf(stderr, "ember: warning: %s\n", name_operand(results[0].warnings[i], operands.names).c_str());
    for (std::size_t k = 0; k < results.size(); ++k) {
      const std::string layer = a.layers ? "layer " + std::to_string(k + 1) + ": " : "";
      for (std::size_t i = shared; i < results[k].warnings.size(); ++i)
        std::fprintf(stderr, "ember: warning: %s%s\n", layer.c_str(),
                     name_operand(results[k].warnings[i], operands.names).c_str());
      const ember::MeshFormat format = ember::format_from_path(outputs[k]);
      const bool float32 =
          format == ember::MeshFormat::Stl || format == ember::MeshFormat::Gltf || format == ember::MeshFormat::Glb;
      if (float32)
        if (const std::size_t bad = ember::stl_degenerate_triangles(results[k].mesh))
          std::fprintf(stderr,
                       "ember: warning: %s: %zu triangles become degenerate in the format's float32 coordinates; "
                       "use .ply, .obj or .off to keep the double coordinates\n",
                       outputs[k].c_str(), bad);
    }
  }
  // All outputs or none: a failed write removes the layers this run wrote.
  for (std::size_t k = 0; k < results.size(); ++k) {
    try {
      write_atomically(results[k].mesh, outputs[k], results[k].provenance);  // PLY keeps it as face properties
    } catch (...) {
      for (std::size_t j = 0; j < k; ++j) fs::remove(outputs[j]);
      throw;
    }
  }
  if (a.stats)
    for (std::size_t k = 0; k < results.size(); ++k)
      ember::cli::print_stats(results[k],
                              (a.layers ? label + " --layers (layer " + std::to_string(k + 1) + ")" : label).c_str(),
                              operands.names);
  return 0;
}

/// `ember eval EXPR`: every file the expression names is one operand (read
/// once, however often it is named), and the expression one Boolean.
int run_eval(const std::string& text, const BooleanArgs& a) {
  const ember::cli::ParsedExpression parsed = ember::cli::parse_expression(text);
  ember::Operation unused = ember::Operation::Union;
  const ember::BooleanOptions options = boolean_options(unused, a, parsed.paths.size());
  ember::format_from_path(a.output);  // reject an unknown output extension before any work
  const ember::ReadOptions read_options = read_options_of(a);
  std::vector<std::string> read_warnings;
  ember::cli::Operands operands;
  for (const std::string& path : parsed.paths) {
    ember::cli::Operands one = ember::cli::read_operands({path}, &read_warnings, &g_activity, read_options);
    if (one.meshes.size() != 1)
      throw ember::Error("holds " + std::to_string(one.meshes.size()) +
                             " objects; in an expression each file is one operand (split the 3MF file, or use "
                             "'ember union' and the other commands, which take each object as an operand)",
                         {.file = path});
    operands.meshes.push_back(std::move(one.meshes[0]));
    operands.names.push_back(path);
  }
  return compute_and_write(operands, read_warnings, options, a, text, [&](const ember::BooleanOptions& o) {
    return std::vector<ember::BooleanResult>{ember::boolean(operands.meshes, parsed.expression, o)};
  });
}

int run_demo(const std::string& dir, int threads) {
  fs::create_directories(dir);
  const ember::Mesh torus = ember::shapes::torus(1.0, 0.35, 96, 48);
  const ember::Mesh sphere = ember::shapes::uv_sphere({0.9, 0.0, 0.2}, 0.6, 64, 32);
  std::printf("ember demo: torus (%zu triangles) and sphere (%zu triangles)\n", torus.triangle_count(),
              sphere.triangle_count());
  write_atomically(torus, fs::path(dir) / "torus.obj");
  write_atomically(sphere, fs::path(dir) / "sphere.obj");
  ember::BooleanOptions options;
  options.threads = threads;
  options.all_solid = true;  // both generated solids are closed, outward and free of self-intersections
  for (const ember::Operation op :
       {ember::Operation::Union, ember::Operation::Intersection, ember::Operation::Difference}) {
    const ember::BooleanResult r = ember::boolean({torus, sphere}, op, options);
    const fs::path out = fs::path(dir) / (std::string(operation_name(op)) + ".obj");
    write_atomically(r.mesh, out);
    std::printf("  %-13s -> %s: %zu triangles in %.1f ms (%d threads)\n", operation_name(op), out.c_str(),
                r.stats.output_polygons, r.stats.time_ms, r.stats.threads);
  }
  return 0;
}

/// The options every Boolean command takes (all but --min-k).
void add_boolean_options(CLI::App* sub, BooleanArgs& args) {
  sub->add_option("-o,--output", args.output, "Output mesh; format from extension")->required();
  sub->add_option("--threads", args.threads, "Worker threads (0 = all cores; results are identical)");
  sub->add_option("--max-3mf-triangles", args.max_3mf_triangles,
                  "Refuse a 3MF file whose components expand to more triangles (default 100000000)");
  sub->add_option("--max-3mf-instancing", args.max_3mf_instancing,
                  "Refuse a 3MF file expanding to over 1 million triangles and this many times what it stores "
                  "(default 1000)");
  sub->add_flag("--stats", args.stats, "Print one JSON object with timing and counts on stderr");
  sub->add_flag("--allow-open", args.allow_open, "Accept inputs that are not closed (warns)");
  sub->add_flag("--quiet", args.quiet, "No warnings and no progress bar on stderr (errors are still printed)");
  sub->add_flag("--assume-solid", args.assume_solid,
                "Promise every input is solid (closed, outward, no self-intersections, no nested or touching "
                "components): skips the solid check; a false promise gives a wrong result");
  sub->add_flag("--no-solid-check", args.no_solid_check,
                "Do not try to prove inputs solid (by default each closed input is checked exactly and, "
                "if solid, takes the fast path); saves the check's time on inputs known to fail it");
  sub->add_flag("--polygons", args.polygons,
                "Write the exact core's raw convex pieces (T-junctions, as in the paper) instead of the "
                "default watertight triangle mesh");
}

}  // namespace

int main(int argc, char** argv) {
  ember::cap_malloc_arenas();  // before any thread starts (ember/process.hpp)
  CLI::App app{"ember: exact mesh Booleans (EMBER). Formats by extension: .obj .stl .ply .off .3mf .gltf .glb"};
  app.require_subcommand(1);
  BooleanArgs args;
  struct Command {
    const char* name;
    ember::Operation op;
    const char* help;
  };
  const Command commands[] = {
      {"union", ember::Operation::Union, "Solid inside any input (with --min-k K: inside at least K inputs)"},
      {"intersection", ember::Operation::Intersection, "Solid inside every input"},
      {"difference", ember::Operation::Difference, "Solid inside the first input and outside all others"},
      {"xor", ember::Operation::Xor, "Solid inside an odd number of inputs"},
  };
  std::vector<std::pair<CLI::App*, ember::Operation>> subs;
  for (const Command& c : commands) {
    CLI::App* sub = app.add_subcommand(c.name, c.help);
    sub->add_option("inputs", args.inputs, "Input meshes (two or more operands; each object of a 3MF file is one)")
        ->required()
        ->expected(1, -1);  // 2 operands: counted after reading (a 3MF file may hold several)
    sub->add_option("--min-k", args.min_k, "union only: keep the solid inside at least K operands (1..operands)");
    sub->add_flag("--layers", args.layers,
                  "union only: write every layer from one pass: OUT-1.ext (inside at least 1 input) .. OUT-N.ext "
                  "(inside all N)");
    add_boolean_options(sub, args);
    subs.emplace_back(sub, c.op);
  }
  std::string expression;
  CLI::App* eval = app.add_subcommand("eval", "Evaluate a CSG expression over mesh files in one Boolean");
  eval->add_option("expression", expression,
                   "Files combined with | (union) & (intersection) - (difference) ^ (xor) and parentheses, "
                   "e.g. '(a.obj | b.stl) - c.ply'; mixed operators need parentheses; quote names with spaces "
                   "or operator characters inside the expression")
      ->required();
  add_boolean_options(eval, args);
  std::string demo_dir = "ember-demo";
  std::string demo_threads = "0";
  CLI::App* demo = app.add_subcommand("demo", "Run all operations on two built-in solids, write OBJ files");
  demo->add_option("-o,--output", demo_dir, "Directory for the demo's meshes")->capture_default_str();
  demo->add_option("--threads", demo_threads, "Worker threads (0 = all cores)");
  app.set_version_flag("--version", std::string("ember ") + EMBER_VERSION);
  ember::cli::install_cleanup_handlers();

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    if (e.get_exit_code() == 0) return app.exit(e);
    std::fprintf(stderr, "ember: %s (see 'ember --help')\n", e.what());
    return 2;
  }
  try {
    if (demo->parsed())
      return run_demo(demo_dir, ember::cli::parse_int_option("--threads", demo_threads, 0, 1 << 16, kThreadsRange));
    for (const auto& [sub, op] : subs)
      if (sub->parsed()) return run_boolean(op, args);
    if (eval->parsed()) return run_eval(expression, args);
  } catch (const ember::cli::UsageError& e) {
    std::fprintf(stderr, "ember: %s (see 'ember --help')\n", e.what());
    return 2;
  } catch (const ember::Error& e) {
    std::fprintf(stderr, "ember: %s\n", e.what());
    return 1;
  } catch (const std::bad_alloc&) {
    // No output was written: results reach the output file only when complete.
    std::fprintf(stderr, "ember: out of memory%s%s; free memory or use smaller inputs\n",
                 g_activity.empty() ? "" : " while ", g_activity.c_str());
    return 1;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "ember: unexpected error: %s\n", e.what());
    return 1;
  }
  return 2;
}
