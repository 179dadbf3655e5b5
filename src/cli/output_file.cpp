// Atomic, private result files (see output_file.hpp).
#include "cli/output_file.hpp"

#include <fcntl.h>
#include <signal.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstdlib>
#include <cstring>
#include <optional>
#include <thread>

#include "ember/error.hpp"

namespace ember::cli {

namespace {

// The pending temporary file, readable from a signal handler: a fixed buffer
// and a flag (no allocation, no locks in the handler).
char g_pending[4096];
volatile sig_atomic_t g_has_pending = 0;

extern "C" void remove_pending_and_die(int sig) {
  if (g_has_pending) ::unlink(g_pending);
  ::signal(sig, SIG_DFL);
  ::raise(sig);
}

/// The signals that end the process by default and are sent by users or
/// terminals (Ctrl-C, Ctrl-\\, a closed terminal, kill): each removes the
/// pending temporary file first.
constexpr int kCleanupSignals[] = {SIGINT, SIGTERM, SIGHUP, SIGQUIT};

/// Blocks the cleanup signals while the pending path changes, so the handler
/// never sees a half-written name or misses a file that already exists.
class SignalBlock {
 public:
  SignalBlock() {
    sigset_t set;
    sigemptyset(&set);
    for (const int sig : kCleanupSignals) sigaddset(&set, sig);
    ::sigprocmask(SIG_BLOCK, &set, &old_);
  }
  ~SignalBlock() { ::sigprocmask(SIG_SETMASK, &old_, nullptr); }
  SignalBlock(const SignalBlock&) = delete;
  SignalBlock& operator=(const SignalBlock&) = delete;

 private:
  sigset_t old_;
};

std::string system_reason() { return std::strerror(errno); }

[[noreturn]] void fail(const std::filesystem::path& out, const std::string& what) {
  throw Error(out.string() + ": " + what);
}

/// Refuses to replace anything but a regular file: rename() would silently
/// swap out a symlink (not its target) or fail late on a directory. A
/// read-only file is refused too, as other tools refuse to overwrite it.
/// Returns the mode of the file being replaced (none: there is none).
std::optional<mode_t> check_replaceable(const std::filesystem::path& out) {
  struct stat st {};
  if (::lstat(out.c_str(), &st) != 0) return std::nullopt;  // absent (or unreadable: creating the temp file says why)
  if (!S_ISREG(st.st_mode)) {
    const char* kind = S_ISDIR(st.st_mode) ? "a directory" : S_ISLNK(st.st_mode) ? "a symbolic link" : "a special file";
    fail(out, std::string("exists and is ") + kind +
                  ", not a regular file; refusing to replace it (remove it or choose another -o)");
  }
  // access() is the user's permission; root passes it for any file, so a file
  // without any write bit counts as read-only for root too.
  if (::access(out.c_str(), W_OK) != 0 || (st.st_mode & 0222) == 0)
    fail(out,
         "exists and is read-only (no write permission); refusing to replace it (make it writable, remove "
         "it or choose another -o)");
  return st.st_mode & 07777;
}

/// Removes the temporary file and forgets it.
void discard(const std::string& tmp) {
  SignalBlock block;
  ::unlink(tmp.c_str());
  g_has_pending = 0;
}

void write_all(int fd, const std::string& bytes, const std::string& tmp, const std::filesystem::path& out) {
  std::size_t done = 0;
  while (done < bytes.size()) {
    const ssize_t n = ::write(fd, bytes.data() + done, bytes.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) {
      const std::string reason = system_reason();
      ::close(fd);
      discard(tmp);
      fail(out, "write failed: " + reason);
    }
    done += static_cast<std::size_t>(n);
  }
}

}  // namespace

void install_cleanup_handlers() {
  struct sigaction sa {};
  sa.sa_handler = remove_pending_and_die;
  sigemptyset(&sa.sa_mask);
  for (const int sig : kCleanupSignals) {
    // Under nohup SIGHUP is ignored on purpose and stays so. (Shells also
    // ignore SIGINT/SIGQUIT for background jobs; a kill -INT is still meant
    // to stop ember, as it always has.)
    struct sigaction old {};
    if (sig == SIGHUP && ::sigaction(sig, nullptr, &old) == 0 && old.sa_handler == SIG_IGN) continue;
    ::sigaction(sig, &sa, nullptr);
  }
}

void write_file_atomically(const std::string& bytes, const std::filesystem::path& out) {
  const std::optional<mode_t> existing_mode = check_replaceable(out);
  const std::filesystem::path dir = out.has_parent_path() ? out.parent_path() : std::filesystem::path(".");
  std::string name = ".";  // hidden, beside the output; built with += (GCC 12 warns spuriously on "." + string)
  name += out.filename().string();
  name += ".ember-XXXXXX";
  std::string tmp = (dir / name).string();
  if (tmp.size() >= sizeof g_pending) fail(out, "path too long for a temporary file beside it");
  int fd = -1;
  {
    SignalBlock block;
    fd = ::mkostemp(tmp.data(), O_CLOEXEC);  // O_CREAT | O_EXCL, mode 0600
    if (fd < 0) fail(out, "cannot open for writing: " + system_reason());
    std::memcpy(g_pending, tmp.c_str(), tmp.size() + 1);
    g_has_pending = 1;
  }
  write_all(fd, bytes, tmp, out);
  // mkstemp's 0600 is for the time the file is incomplete; the result keeps
  // the mode of the file it replaces, or gets the mode an ordinary new file
  // would get (0666 minus the umask).
  const mode_t mask = ::umask(0);
  ::umask(mask);
  std::string problem;
  if (::fchmod(fd, existing_mode ? *existing_mode : 0666 & ~mask) != 0)
    problem = "cannot set the file mode: " + system_reason();
  if (::close(fd) != 0 && problem.empty()) problem = "write failed: " + system_reason();  // e.g. disk full on NFS
  if (!problem.empty()) {
    discard(tmp);
    fail(out, problem);
  }
  // Test hook: hold the finished temporary file so that tests can interrupt
  // the process at this point and check the cleanup.
  if (const char* hold = std::getenv("EMBER_TEST_HOLD_TEMP_MS"))
    std::this_thread::sleep_for(std::chrono::milliseconds(std::atoi(hold)));
  if (::rename(tmp.c_str(), out.c_str()) != 0) {
    const std::string reason = system_reason();
    discard(tmp);
    fail(out, "cannot move the result into place: " + reason);
  }
  SignalBlock block;
  g_has_pending = 0;
}

}  // namespace ember::cli
