#pragma once
// Helpers for the CLI tests: a fresh temporary directory per test, running the
// built `ember` binary through the shell with stdout and stderr captured to
// files, and small file utilities.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <atomic>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <initializer_list>
#include <iterator>
#include <set>
#include <sstream>
#include <string>
#include <vector>

namespace ember::clitest {

namespace fs = std::filesystem;

inline std::string read_file(const fs::path& p) {
  std::ifstream f(p, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(f), std::istreambuf_iterator<char>());
}

inline void write_file(const fs::path& p, const std::string& bytes) {
  std::ofstream f(p, std::ios::binary | std::ios::trunc);
  f.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  ASSERT_TRUE(f.good()) << "cannot write " << p;
}

/// Lines of a text (without the '\n'); a final line without '\n' counts too.
inline std::vector<std::string> lines_of(const std::string& text) {
  std::vector<std::string> out;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) out.push_back(line);
  return out;
}

/// A fresh directory under the system temp directory, removed on destruction.
/// `work()` is where the test puts inputs and outputs; the captured stdout and
/// stderr of runs go to a sibling folder so that directory listings of
/// `work()` only show what the CLI wrote.
class TempDir {
 public:
  TempDir() {
    static std::atomic<int> counter{0};
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    std::string name = "ember_cli_test_";
    name += std::to_string(::getpid());
    name += '_';
    name += std::to_string(counter++);
    if (info) name += std::string("_") + info->name();
    for (char& c : name)
      if (c == '/') c = '_';
    root_ = fs::temp_directory_path() / name;
    fs::remove_all(root_);
    fs::create_directories(root_ / "work");
    fs::create_directories(root_ / "io");
  }
  ~TempDir() {
    std::error_code ec;
    fs::remove_all(root_, ec);
  }
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;

  fs::path work() const { return root_ / "work"; }
  fs::path io() const { return root_ / "io"; }
  fs::path operator/(const std::string& name) const { return work() / name; }

  /// Names of the entries directly in work(), sorted.
  std::set<std::string> listing() const {
    std::set<std::string> out;
    for (const auto& e : fs::directory_iterator(work())) out.insert(e.path().filename().string());
    return out;
  }

 private:
  fs::path root_;
};

struct RunResult {
  int exit_code = -1;     ///< WEXITSTATUS, or -1 if the process did not exit normally
  bool signaled = false;  ///< killed by a signal (crash)
  std::string out, err;   ///< captured stdout and stderr
  std::string command;    ///< the shell command, for failure messages
};

inline std::string shell_quote(const std::string& s) {
  std::string q = "'";
  for (char c : s) {
    if (c == '\'')
      q += "'\\''";
    else
      q += c;
  }
  return q + "'";
}

inline std::string cli_path() { return EMBER_CLI_PATH; }

/// Runs `ember args...` in dir.work() (so relative paths resolve there).
inline RunResult run_cli(const TempDir& dir, const std::vector<std::string>& args) {
  static std::atomic<int> run_counter{0};
  const int id = run_counter++;
  const std::string suffix = std::to_string(id) + ".txt";
  const fs::path out = dir.io() / (std::string("stdout_") += suffix);
  const fs::path err = dir.io() / (std::string("stderr_") += suffix);
  // Built with += only (GCC 12 warns spuriously about "literal" + std::string&&).
  std::string cmd = "cd ";
  cmd += shell_quote(dir.work().string());
  cmd += " && ";
  cmd += shell_quote(cli_path());
  for (const std::string& a : args) {
    cmd += ' ';
    cmd += shell_quote(a);
  }
  std::string full = cmd;
  full += " >";
  full += shell_quote(out.string());
  full += " 2>";
  full += shell_quote(err.string());
  full += " </dev/null";
  RunResult r;
  r.command = cmd;
  const int status = std::system(full.c_str());
  if (status != -1 && WIFEXITED(status)) {
    r.exit_code = WEXITSTATUS(status);
    // The shell reports a child killed by signal N as 128 + N.
    r.signaled = r.exit_code > 128;
  } else {
    r.signaled = status != -1 && WIFSIGNALED(status);
  }
  r.out = read_file(out);
  r.err = read_file(err);
  return r;
}

inline std::string describe(const RunResult& r) {
  return "command: " + r.command + "\nexit: " + std::to_string(r.exit_code) + "\nstdout:\n" + r.out + "\nstderr:\n" +
         r.err;
}

}  // namespace ember::clitest
