#pragma once
// Writing the CLI's result files without ever leaving a partial or foreign
// file behind: the bytes go to a private temporary file created in the
// output's folder (O_EXCL, so a planted file or symlink is never followed),
// which is renamed onto the output only when complete. The temporary file is
// removed on every failure and on SIGINT, SIGTERM, SIGHUP and SIGQUIT. A
// replaced file keeps its mode; a read-only one is refused.
#include <filesystem>
#include <string>

namespace ember::cli {

/// Installs the SIGINT/SIGTERM/SIGHUP/SIGQUIT handlers that remove a pending temporary file
/// before the process dies. Call once at start-up.
void install_cleanup_handlers();

/// Writes `bytes` to `out` atomically (see above). Throws ember::Error with the
/// system's reason on failure. An existing `out` that is not a regular file
/// (directory, symlink, device, ...) is refused rather than replaced.
void write_file_atomically(const std::string& bytes, const std::filesystem::path& out);

}  // namespace ember::cli
