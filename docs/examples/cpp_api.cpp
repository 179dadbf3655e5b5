// The example of docs/cpp-api.md. The build compiles it (ember_example_cpp,
// run by ctest as docs.cpp_api_example) and the install test compiles it again
// as a find_package(ember) consumer (tests/install_consumer).
//
//   cpp_api_example [DIR]   writes DIR/torus.3mf and DIR/difference.obj (DIR: current directory)
#include <cstdio>
#include <filesystem>

#include <ember/boolean.hpp>
#include <ember/csg.hpp>
#include <ember/error.hpp>
#include <ember/io/mesh_io.hpp>
#include <ember/shapes.hpp>

int main(int argc, char** argv) {
  const std::filesystem::path dir = argc > 1 ? argv[1] : ".";
  try {
    const ember::Mesh torus = ember::shapes::torus(1.0, 0.35, 48, 24);
    const ember::Mesh sphere = ember::shapes::uv_sphere({0.9, 0.0, 0.2}, 0.6, 32, 16);

    // Any number of operands; options are optional.
    ember::BooleanOptions options;
    options.threads = 0;  // all cores; the result does not depend on it
    options.progress = [](std::string_view phase, double fraction) {
      std::fprintf(stderr, "  %-12.*s %3.0f%%\n", int(phase.size()), phase.data(), 100 * fraction);
    };
    const ember::BooleanResult diff = ember::boolean({torus, sphere}, ember::Operation::Difference, options);
    std::printf("difference: %zu polygons, %zu solid operands, %.1f ms\n", diff.mesh.face_count(),
                diff.stats.solid_operands, diff.stats.time_ms);
    // Provenance: every output face names the operand and face it lies on.
    const ember::Provenance p = diff.provenance.front();
    std::printf("face 0 comes from operand %u, face %u\n", p.operand, p.face);

    // Files: the format follows the extension (.obj .stl .off .ply .3mf).
    ember::write_mesh(diff.mesh, dir / "difference.obj");
    ember::write_mesh(torus, dir / "torus.3mf");
    const ember::Mesh back = ember::read_mesh(dir / "torus.3mf");  // 3MF stores floats: coordinates round
    const ember::BooleanResult uni = ember::boolean({back, sphere}, ember::Operation::Union);
    std::printf("union of torus.3mf and the sphere: %zu polygons\n", uni.mesh.face_count());

    // Any CSG expression in one Boolean: operands by index, each quantized once.
    const ember::Csg t = ember::Csg::operand(0), s = ember::Csg::operand(1);
    const ember::BooleanResult shell = ember::boolean({torus, sphere}, (t | s) - (t & s));
    std::printf("(torus | sphere) - (torus & sphere): %zu polygons\n", shell.mesh.face_count());

    // Bad input is an ember::Error whose message says what to fix.
    ember::Mesh broken = torus;
    broken.indices[0] = 1u << 30;
    ember::boolean({broken, sphere}, ember::Operation::Union);
    std::fprintf(stderr, "expected an error for a bad index\n");
    return 1;
  } catch (const ember::Error& e) {
    std::printf("error (as expected): %s\n", e.what());
    return 0;
  }
}
