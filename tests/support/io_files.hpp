#pragma once
// Small helpers shared by the I/O tests: sample meshes and error capture.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <initializer_list>
#include <string>
#include <vector>

#include "ember/error.hpp"
#include "ember/mesh.hpp"
#include "ember/shapes.hpp"

namespace ember::test {

/// The ember::Error message thrown by f, or a test failure if none is thrown.
template <class F>
std::string error_of(F&& f) {
  try {
    f();
  } catch (const Error& e) {
    return e.what();
  }
  ADD_FAILURE() << "expected an ember::Error";
  return {};
}

#define EXPECT_ERROR_HAS(call, ...)                                                               \
  do {                                                                                            \
    const std::string msg_ = ::ember::test::error_of([&] { (void)(call); });                      \
    for (const std::string& part_ : std::initializer_list<std::string>{__VA_ARGS__})              \
      EXPECT_NE(msg_.find(part_), std::string::npos) << "'" << part_ << "' missing in: " << msg_; \
  } while (0)

/// Unit cube with quad faces, outward orientation.
inline Mesh cube_quads() {
  Mesh m;
  for (int i = 0; i < 8; ++i) m.add_vertex({double(i & 1), double((i >> 1) & 1), double((i >> 2) & 1)});
  m.add_face({0, 2, 3, 1});
  m.add_face({4, 5, 7, 6});
  m.add_face({0, 1, 5, 4});
  m.add_face({2, 6, 7, 3});
  m.add_face({0, 4, 6, 2});
  m.add_face({1, 3, 7, 5});
  return m;
}

/// A mesh whose coordinates need all 17 significant digits, plus -0.0, tiny,
/// huge and subnormal values, and faces of 3, 4 and 5 vertices.
inline Mesh awkward_mesh() {
  Mesh m;
  m.add_vertex({0.1, 1.0 / 3.0, -0.0});
  m.add_vertex({1e-300, 4.9e-324, 2.5});
  m.add_vertex({-1e300, 123456789.123456789, -7.0});
  m.add_vertex({std::nextafter(1.0, 2.0), -2.0 / 7.0, 1e-7});
  m.add_vertex({3.0, 3.0, 3.0});
  m.add_vertex({-0.5, 0.25, 1e22});
  m.add_face({0, 1, 2});
  m.add_face({0, 2, 3, 4});
  m.add_face({1, 2, 3, 4, 5});
  return m;
}

/// UV sphere: closed triangle mesh with (rings-1)*segments+2 vertices.
inline Mesh uv_sphere(int rings, int segments) { return shapes::uv_sphere({0, 0, 0}, 1.0, segments, rings); }

/// Exact equality including the sign of zero (operator== treats -0.0 == 0.0).
inline bool bit_identical(const Mesh& a, const Mesh& b) {
  if (!(a == b)) return false;
  return std::memcmp(a.vertices.data(), b.vertices.data(), a.vertices.size() * sizeof(Vec3d)) == 0;
}

/// Checks the invariants every mesh a reader returns must satisfy.
inline void expect_well_formed(const Mesh& m) {
  ASSERT_FALSE(m.face_offsets.empty());
  EXPECT_EQ(m.face_offsets.front(), 0u);
  EXPECT_EQ(m.face_offsets.back(), m.indices.size());
  for (std::size_t f = 0; f < m.face_count(); ++f) EXPECT_GE(m.face_size(f), 3u);
  for (auto i : m.indices) EXPECT_LT(i, m.vertices.size());
  for (const auto& v : m.vertices) EXPECT_TRUE(std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z));
}

}  // namespace ember::test
