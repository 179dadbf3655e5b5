// All layers at once (boolean_layers, the paper's Fig. 21): layer k is the
// solid inside at least k operands. Checked against the AtLeastK operation,
// the layer-cake identity (the layers' volumes add up to the operands'),
// winding numbers at sample points, exact box volumes, and bit-identical
// output at 1 and 2 threads, on the solid path and the general path.
#include <gtest/gtest.h>

#include "support/boolean_checks.hpp"

namespace ember::test {
namespace {

using Op = Operation;

TEST(Layers, EachLayerIsTheAtLeastKSolidAndTheyStackUpToTheOperands) {
  const std::vector<Mesh> ops = four_solids();
  for (const BooleanOptions& options : {BooleanOptions{}, general_path()}) {
    const std::vector<BooleanResult> layers = boolean_layers(ops, options);
    ASSERT_EQ(layers.size(), ops.size());
    double stacked = 0;
    for (std::size_t k = 1; k <= layers.size(); ++k) {
      const BooleanResult& layer = layers[k - 1];
      BooleanOptions at_least = options;
      at_least.min_k = static_cast<int>(k);
      const BooleanResult reference = boolean(ops, Op::AtLeastK, at_least);
      EXPECT_TRUE(close_rel(volume(layer.mesh), volume(reference.mesh), 1e-9)) << "layer " << k;
      EXPECT_TRUE(close_rel(surface_area(layer.mesh), surface_area(reference.mesh), 1e-9)) << "layer " << k;
      expect_watertight_if_closed(ops, options, layer);
      EXPECT_EQ(face_problems(layer.mesh), "") << "layer " << k;
      EXPECT_EQ(layer.provenance.size(), layer.mesh.face_count());
      EXPECT_EQ(layer.stats.diagnostic("direct_mesh"), 0.0);
      const MembershipReport m = membership_check(ops, Op::AtLeastK, layer.mesh, 200, 23 + k, static_cast<int>(k));
      EXPECT_EQ(m.mismatches, 0) << "layer " << k << ": " << m.first;
      stacked += volume(layer.mesh);
    }
    EXPECT_TRUE(close_rel(stacked, volume(std::span<const Mesh>(ops)), 1e-9))
        << stacked << " vs " << volume(std::span<const Mesh>(ops));
    EXPECT_EQ(layers.front().stats.diagnostic("solid_path"), options.detect_solid ? 1.0 : 0.0);
  }
}

TEST(Layers, BoxLayersHaveTheExactVoxelVolumes) {
  const std::vector<std::vector<Box>> boxes{{{{0, 0, 0}, {4, 4, 4}}},
                                            {{{1, 1, 1}, {5, 5, 5}}},
                                            {{{2, 0, 1}, {3, 6, 3}}},
                                            {{{0, 2, 2}, {6, 3, 6}}},
                                            {{{1, 1, 0}, {3, 3, 7}}}};
  const std::vector<Mesh> ops = box_meshes(boxes);
  const std::vector<BooleanResult> layers = boolean_layers(ops);
  for (std::size_t k = 1; k <= layers.size(); ++k) {
    EXPECT_EQ(volume(layers[k - 1].mesh),
              voxel_volume(boxes, reference_indicator(Op::AtLeastK, 5, static_cast<int>(k))))
        << "layer " << k;
    EXPECT_EQ(provenance_plane_violations(ops, layers[k - 1]), 0);
  }
}

TEST(Layers, TwoOperandsGiveTheUnionAndTheIntersection) {
  const std::vector<Mesh> all = four_solids();
  const std::span<const Mesh> ab(all.data(), 2);
  const std::vector<BooleanResult> layers = boolean_layers(ab);
  ASSERT_EQ(layers.size(), 2u);
  EXPECT_TRUE(close_rel(volume(layers[0].mesh), volume(boolean(ab, Op::Union).mesh), 1e-9));
  EXPECT_TRUE(close_rel(volume(layers[1].mesh), volume(boolean(ab, Op::Intersection).mesh), 1e-9));
}

TEST(Layers, OneAndTwoThreadsGiveIdenticalBytes) {
  const std::vector<Mesh> ops = four_solids();
  for (BooleanOptions options : {BooleanOptions{}, general_path()}) {
    options.threads = 1;
    const std::vector<BooleanResult> one = boolean_layers(ops, options);
    options.threads = 2;
    const std::vector<BooleanResult> two = boolean_layers(ops, options);
    ASSERT_EQ(one.size(), two.size());
    for (std::size_t k = 0; k < one.size(); ++k) {
      EXPECT_EQ(one[k].mesh.indices, two[k].mesh.indices) << "layer " << k + 1;
      ASSERT_EQ(one[k].mesh.vertices.size(), two[k].mesh.vertices.size());
      for (std::size_t v = 0; v < one[k].mesh.vertices.size(); ++v) {
        const Vec3d p = one[k].mesh.vertices[v], q = two[k].mesh.vertices[v];
        ASSERT_TRUE(p.x == q.x && p.y == q.y && p.z == q.z) << "layer " << k + 1 << " vertex " << v;
      }
    }
  }
}

TEST(Layers, OptionsThatFixOneResultAreRefused) {
  const std::vector<Mesh> ops = four_solids();
  BooleanOptions k;
  k.min_k = 2;
  EXPECT_NE(error_message([&] { boolean_layers(ops, k); }).find("min_k does not apply"), std::string::npos);
  BooleanOptions custom;
  custom.indicator = [](WindingVector) { return true; };
  EXPECT_NE(error_message([&] { boolean_layers(ops, custom); }).find("indicator does not apply"), std::string::npos);
  EXPECT_NE(error_message([&] { boolean_layers(std::span<const Mesh>(), {}); }).find("no operands"), std::string::npos);
}

}  // namespace
}  // namespace ember::test
