#include "core/output/properties.hpp"

#include <algorithm>
#include <array>
#include <cmath>

#include "ember/error.hpp"

namespace ember::core {

namespace {

struct V3 {
  double x, y, z;
};
double dot(const V3& a, const V3& b) { return a.x * b.x + a.y * b.y + a.z * b.z; }

/// The Newell normal of a face (not normalized): robust for any planar polygon.
V3 face_normal(const Mesh& m, std::span<const std::uint32_t> face) {
  V3 n{0, 0, 0};
  for (std::size_t i = 0; i < face.size(); ++i) {
    const Vec3d& a = m.vertices[face[i]];
    const Vec3d& b = m.vertices[face[(i + 1) % face.size()]];
    n.x += (a.y - b.y) * (a.z + b.z);
    n.y += (a.z - b.z) * (a.x + b.x);
    n.z += (a.x - b.x) * (a.y + b.y);
  }
  return n;
}

/// Barycentric coordinates of p in triangle a, b, c, projected along the
/// normal's dominant axis (p lies in the plane up to rounding).
std::array<double, 3> barycentric(const Vec3d& p, const Vec3d& a, const Vec3d& b, const Vec3d& c, const V3& n) {
  const double ax = std::abs(n.x), ay = std::abs(n.y), az = std::abs(n.z);
  const auto uv = [&](const Vec3d& q) -> std::array<double, 2> {
    if (ax >= ay && ax >= az) return {q.y, q.z};
    if (ay >= az) return {q.z, q.x};
    return {q.x, q.y};
  };
  const auto P = uv(p), A = uv(a), B = uv(b), C = uv(c);
  const double d = (B[0] - A[0]) * (C[1] - A[1]) - (C[0] - A[0]) * (B[1] - A[1]);
  if (d == 0) return {1.0, 0.0, 0.0};
  const double l1 = ((P[0] - A[0]) * (C[1] - A[1]) - (C[0] - A[0]) * (P[1] - A[1])) / d;
  const double l2 = ((B[0] - A[0]) * (P[1] - A[1]) - (P[0] - A[0]) * (B[1] - A[1])) / d;
  return {1.0 - l1 - l2, l1, l2};
}

const MeshProperty* find(const Mesh& m, const std::string& name) {
  for (const MeshProperty& p : m.properties)
    if (p.name == name) return &p;
  return nullptr;
}

}  // namespace

PropertyPlan PropertyPlan::of(std::span<const Mesh> operands) {
  PropertyPlan plan;
  for (std::size_t o = 0; o < operands.size(); ++o) {
    const Mesh& m = operands[o];
    for (const MeshProperty& p : m.properties) {
      const std::size_t elements = p.per_corner ? m.indices.size() : m.vertices.size();
      if (p.width == 0 || p.width > 16)
        throw Error("property '" + p.name + "' has width " + std::to_string(p.width) + "; give 1 to 16 floats",
                    {.operand = o});
      if (p.values.size() != elements * p.width)
        throw Error("property '" + p.name + "' has " + std::to_string(p.values.size()) + " values; " +
                        std::to_string(elements) + (p.per_corner ? " corners" : " vertices") + " of width " +
                        std::to_string(p.width) + " need " + std::to_string(elements * p.width),
                    {.operand = o});
      if (!std::all_of(p.values.begin(), p.values.end(), [](float v) { return std::isfinite(v); }))
        throw Error("property '" + p.name + "' has a non-finite value", {.operand = o});
      const auto known =
          std::find_if(plan.channels.begin(), plan.channels.end(), [&](const Channel& c) { return c.name == p.name; });
      if (known == plan.channels.end())
        plan.channels.push_back({p.name, p.width});
      else if (known->width != p.width)
        throw Error("property '" + p.name + "' has width " + std::to_string(p.width) + " here but " +
                        std::to_string(known->width) + " in an earlier operand",
                    {.operand = o});
    }
  }
  return plan;
}

namespace {

/// How one output corner mixes its source face's corners: three corners of
/// the fan triangle that holds it (indices into the face) and their weights.
struct CornerMix {
  std::array<std::uint32_t, 3> corner{};  ///< positions within the source face
  std::array<double, 3> weight{};
};

/// The mixes of every corner of output face f and its (unnormalized)
/// normal; returns whether the Boolean reversed it against its source face.
bool mix_face(const Mesh& out, std::size_t f, const Mesh& in, std::span<const std::uint32_t> source,
              std::vector<CornerMix>& mixes, V3& n_out) {
  const std::span<const std::uint32_t> face = out.face(f);
  const V3 n_in = face_normal(in, source);
  mixes.resize(face.size());
  for (std::size_t k = 0; k < face.size(); ++k) {
    const Vec3d& pos = out.vertices[face[k]];
    double best_min = -1e300;
    for (std::uint32_t i = 1; i + 1 < source.size(); ++i) {
      const auto b = barycentric(pos, in.vertices[source[0]], in.vertices[source[i]], in.vertices[source[i + 1]], n_in);
      const double lowest = std::min({b[0], b[1], b[2]});
      if (lowest <= best_min) continue;
      best_min = lowest;
      mixes[k].corner = {0, i, i + 1};
      mixes[k].weight = b;
    }
  }
  n_out = face_normal(out, face);
  return dot(n_out, n_in) < 0;
}

}  // namespace

std::vector<std::string> interpolate_properties(const PropertyPlan& plan, std::span<const Mesh> operands,
                                                std::span<const Provenance> provenance, Mesh& out) {
  std::vector<std::string> warnings;
  // Per channel: the result, and per operand its own property (or none).
  std::vector<MeshProperty> results;
  std::vector<std::vector<const MeshProperty*>> source_of(plan.channels.size());
  std::vector<std::vector<char>> lacking(plan.channels.size(), std::vector<char>(operands.size(), 0));
  for (std::size_t ch = 0; ch < plan.channels.size(); ++ch) {
    const PropertyPlan::Channel& c = plan.channels[ch];
    results.push_back({c.name, c.width, true, std::vector<float>(out.indices.size() * c.width, 0.0f)});
    for (const Mesh& m : operands) source_of[ch].push_back(find(m, c.name));
  }
  std::vector<CornerMix> mixes;
  for (std::size_t f = 0; f < out.face_count(); ++f) {
    const Provenance src = provenance[f];
    const Mesh& in = operands[src.operand];
    const std::span<const std::uint32_t> face = out.face(f), source = in.face(src.face);
    V3 n_out;
    const bool reversed = mix_face(out, f, in, source, mixes, n_out);
    for (std::size_t ch = 0; ch < plan.channels.size(); ++ch) {
      const std::uint32_t width = plan.channels[ch].width;
      const bool normal = plan.channels[ch].name == "normal" && width == 3;
      const MeshProperty* p = source_of[ch][src.operand];
      for (std::size_t k = 0; k < face.size(); ++k) {
        float* dst = results[ch].values.data() + (out.face_offsets[f] + k) * width;
        if (!p) {
          lacking[ch][src.operand] = 1;
          if (normal) {  // the face's own normal
            const double len = std::sqrt(dot(n_out, n_out));
            if (len > 0) dst[0] = float(n_out.x / len), dst[1] = float(n_out.y / len), dst[2] = float(n_out.z / len);
          }
          continue;
        }
        const CornerMix& mix = mixes[k];
        for (int j = 0; j < 3; ++j) {
          const std::size_t e = p->per_corner ? in.face_offsets[src.face] + mix.corner[j] : source[mix.corner[j]];
          const float* v = p->values.data() + e * width;
          for (std::uint32_t w = 0; w < width; ++w) dst[w] += static_cast<float>(mix.weight[j] * v[w]);
        }
        if (normal) {
          const double len = std::sqrt(double(dst[0]) * dst[0] + double(dst[1]) * dst[1] + double(dst[2]) * dst[2]);
          const double s = len > 0 ? (reversed ? -1.0 : 1.0) / len : 0.0;
          for (int j = 0; j < 3; ++j) dst[j] = static_cast<float>(dst[j] * s);
        }
      }
    }
  }
  for (std::size_t ch = 0; ch < plan.channels.size(); ++ch) {
    for (std::size_t o = 0; o < operands.size(); ++o)
      if (lacking[ch][o])
        warnings.push_back("operand " + std::to_string(o) + ": has no property '" + plan.channels[ch].name +
                           "'; its faces get " + (plan.channels[ch].name == "normal" ? "their own normals" : "zeros"));
    out.properties.push_back(std::move(results[ch]));
  }
  return warnings;
}

}  // namespace ember::core
