// Without libFuzzer: runs a fuzz target once on every file given, and on
// every file of every folder given whose extension matches EMBER_FUZZ_EXT
// (smaller than 64 KiB: a seed corpus is small files). Exit status 77 (a
// skipped test for ctest) when a folder is missing and nothing was run.
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size);

namespace fs = std::filesystem;

namespace {

bool run_file(const fs::path& p) {
  std::ifstream f(p, std::ios::binary);
  const std::string bytes((std::istreambuf_iterator<char>(f)), std::istreambuf_iterator<char>());
  if (!f.good() && !f.eof()) return false;
  LLVMFuzzerTestOneInput(reinterpret_cast<const std::uint8_t*>(bytes.data()), bytes.size());
  return true;
}

bool matches(const fs::path& p) {
  std::string ext = p.extension().string();
  for (char& c : ext) c = static_cast<char>(c >= 'A' && c <= 'Z' ? c - 'A' + 'a' : c);
  return ext == EMBER_FUZZ_EXT;
}

}  // namespace

int main(int argc, char** argv) {
  std::size_t ran = 0;
  bool missing = false;
  for (int i = 1; i < argc; ++i) {
    const fs::path arg = argv[i];
    std::error_code ec;
    if (fs::is_directory(arg, ec)) {
      for (const auto& e : fs::recursive_directory_iterator(arg, ec))
        if (e.is_regular_file() && matches(e.path()) && e.file_size() < (64u << 10)) ran += run_file(e.path());
    } else if (fs::is_regular_file(arg, ec)) {
      ran += run_file(arg);
    } else {
      std::printf("%s: not found\n", argv[i]);
      missing = true;
    }
  }
  std::printf("replayed %zu inputs through the %s reader\n", ran, EMBER_FUZZ_EXT);
  if (ran == 0 && missing) {
    std::printf("skipped: no seed inputs (the shared data folder is absent)\n");
    return 77;
  }
  return 0;
}
