#include "core/input/face_groups.hpp"

#include <algorithm>
#include <map>

#include "ember/error.hpp"

namespace ember::core {

FaceGroups FaceGroups::of(std::span<const Mesh> operands) {
  FaceGroups out;
  if (std::none_of(operands.begin(), operands.end(), [](const Mesh& m) { return !m.face_groups.empty(); })) return out;
  // The key of a group: "n:" + name, or "#" + id for an unnamed one, "" the default.
  std::map<std::string, std::uint32_t> by_key;
  const auto output_group = [&](const std::string& key, const std::string& name) {
    const auto [it, added] = by_key.emplace(key, static_cast<std::uint32_t>(out.names_.size()));
    if (added) out.names_.push_back(name);
    return it->second;
  };
  for (std::size_t o = 0; o < operands.size(); ++o) {
    const Mesh& m = operands[o];
    Operand op;
    if (m.face_groups.empty()) {
      op.default_group = output_group("", "");
      out.per_operand_.push_back(std::move(op));
      continue;
    }
    if (m.face_groups.size() != m.face_count())
      throw Error("face_groups has " + std::to_string(m.face_groups.size()) + " entries for " +
                      std::to_string(m.face_count()) + " faces; give one per face or none",
                  {.operand = o});
    const std::uint32_t largest = *std::max_element(m.face_groups.begin(), m.face_groups.end());
    if (largest >= kMaxGroup)
      throw Error("face group " + std::to_string(largest) + " is too large (groups are numbered below 2^24)",
                  {.operand = o});
    std::vector<char> used(largest + std::size_t{1}, 0);
    for (const std::uint32_t g : m.face_groups) used[g] = 1;
    op.face_groups = m.face_groups;
    op.output.assign(largest + std::size_t{1}, 0);
    for (std::uint32_t g = 0; g <= largest; ++g) {
      if (!used[g]) continue;
      const bool named = g < m.group_names.size() && !m.group_names[g].empty();
      op.output[g] =
          named ? output_group("n:" + m.group_names[g], m.group_names[g]) : output_group(std::string(1, '#').append(std::to_string(g)), "");
    }
    out.per_operand_.push_back(std::move(op));
  }
  return out;
}

std::vector<std::uint32_t> FaceGroups::region_keys(std::span<const Mesh> operands, std::span<const Provenance> sources,
                                                   bool per_face) const {
  std::vector<std::uint32_t> keys;
  if (per_face) {
    std::vector<std::uint32_t> base(operands.size() + 1, 0);
    for (std::size_t o = 0; o < operands.size(); ++o)
      base[o + 1] = base[o] + static_cast<std::uint32_t>(operands[o].face_count());
    keys.resize(sources.size());
    for (std::size_t id = 0; id < sources.size(); ++id) keys[id] = base[sources[id].operand] + sources[id].face;
  } else if (!empty()) {
    keys.resize(sources.size());
    for (std::size_t id = 0; id < sources.size(); ++id) keys[id] = group(sources[id].operand, sources[id].face);
  }
  return keys;
}

void FaceGroups::assign(std::span<const Provenance> provenance, Mesh& out) const {
  if (empty()) return;
  out.face_groups.resize(provenance.size());
  for (std::size_t f = 0; f < provenance.size(); ++f)
    out.face_groups[f] = group(provenance[f].operand, provenance[f].face);
  if (std::any_of(names_.begin(), names_.end(), [](const std::string& n) { return !n.empty(); }))
    out.group_names = names_;
}

std::uint32_t FaceGroups::group(std::uint32_t operand, std::uint32_t face) const {
  const Operand& op = per_operand_[operand];
  return op.face_groups.empty() ? op.default_group : op.output[op.face_groups[face]];
}

}  // namespace ember::core
