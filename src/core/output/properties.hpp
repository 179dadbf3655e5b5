#pragma once
// Properties (Mesh::properties: UVs, normals, colours, ...) of the operands
// carried to a Boolean's output corners by provenance.
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "ember/mesh.hpp"

namespace ember::core {

/// The properties the output gets: every name any operand has, with its
/// width. Throws ember::Error naming the operand for a property of the wrong
/// size, a width that differs between operands, or a non-finite value.
struct PropertyPlan {
  struct Channel {
    std::string name;
    std::uint32_t width = 0;
  };
  std::vector<Channel> channels;
  bool empty() const { return channels.empty(); }
  static PropertyPlan of(std::span<const Mesh> operands);
};

/// Fills `out.properties` (per corner) from the operands: an output corner
/// gets the linear interpolation, in the source face's fan triangle that
/// holds it, of that face's corner values (barycentric coordinates from the
/// corner's double position). An operand without a channel gives zeros, or
/// for "normal" the output face's own normal; normals are renormalized and
/// turned with faces the Boolean reversed. `provenance` has one entry per face.
/// Returns a warning per channel some operand lacks.
std::vector<std::string> interpolate_properties(const PropertyPlan& plan, std::span<const Mesh> operands,
                                                std::span<const Provenance> provenance, Mesh& out);

}  // namespace ember::core
