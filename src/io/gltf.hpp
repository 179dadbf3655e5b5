#pragma once
// The glTF reader with file access (gltf.cpp): external buffers are read
// from below `base`, none when it is empty (reading from memory).
#include <cstdint>
#include <filesystem>
#include <string_view>

#include "ember/mesh.hpp"

namespace ember::io_detail {

Mesh read_gltf(std::string_view bytes, std::string_view name, bool binary, const std::filesystem::path& base,
               std::uint64_t max_triangles);

}  // namespace ember::io_detail
