#pragma once
// A pass over a 3MF package before lib3mf reads it: the component graph's
// expanded size. lib3mf 1.x resolves components instance by instance, so a
// small file whose objects each hold a few components of the previous one
// (a "zip bomb" of components) takes time and memory exponential in the
// depth, inside lib3mf, before any of ember's own checks could run.
//
// The scan reads the ZIP directory, inflates every *.model part with zlib and
// picks the object, triangle, component and build item tags out of the XML;
// it never fails: what it cannot follow is left to lib3mf, which reports it.
#include <cstdint>
#include <optional>
#include <string_view>

namespace ember::io_detail {

struct ThreeMfExpansion {
  std::uint64_t stored_triangles = 0;    ///< triangles written in the file
  std::uint64_t expanded_triangles = 0;  ///< after resolving every build item's components (saturating)
  std::uint64_t instances = 0;           ///< object instances after resolving (saturating)
};

/// The expansion of a 3MF package's build items; none when the package could
/// not be followed (then lib3mf reads and judges it).
std::optional<ThreeMfExpansion> scan_3mf_expansion(std::string_view bytes);

}  // namespace ember::io_detail
