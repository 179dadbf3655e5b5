#pragma once
// The operands' face groups (Mesh::face_groups) as the output's groups.
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "ember/mesh.hpp"

namespace ember::core {

/// Output groups: a named group is one group however many operands use the
/// name; an unnamed group g is one group with every operand's unnamed g; the
/// faces of operands without groups form the unnamed default group.
/// Numbered in order of first appearance (operand by operand, group by group).
class FaceGroups {
 public:
  /// Empty (no groups anywhere) when no operand has face_groups. Throws
  /// ember::Error for face_groups of the wrong size or an id beyond kMaxGroup.
  static FaceGroups of(std::span<const Mesh> operands);

  bool empty() const { return per_operand_.empty(); }
  /// The output group of face `face` of operand `operand`.
  std::uint32_t group(std::uint32_t operand, std::uint32_t face) const;
  /// Per output group its name ("" when unnamed).
  const std::vector<std::string>& names() const { return names_; }
  /// Per source id (`sources[id]` its input face) the key that keeps output
  /// regions apart (build_regions): its face group, or with `per_face` its
  /// input face itself; empty when nothing needs keeping apart.
  std::vector<std::uint32_t> region_keys(std::span<const Mesh> operands, std::span<const Provenance> sources,
                                         bool per_face) const;
  /// Puts each face of `out` in its source face's group (`provenance`, one
  /// per face) and sets the names when any group has one; nothing without groups.
  void assign(std::span<const Provenance> provenance, Mesh& out) const;

  static constexpr std::uint32_t kMaxGroup = 1u << 24;

 private:
  struct Operand {
    std::span<const std::uint32_t> face_groups;  ///< the operand's own (empty: none)
    std::vector<std::uint32_t> output;           ///< its group id -> output group
    std::uint32_t default_group = 0;             ///< for an operand without groups
  };
  std::vector<Operand> per_operand_;
  std::vector<std::string> names_;
};

}  // namespace ember::core
