// ember::cap_malloc_arenas (ember/process.hpp): applies to glibc's malloc
// unless the environment already chooses, and leaves other allocators alone.
#include <gtest/gtest.h>

#include <cstdlib>
#include <string>

#include "ember/process.hpp"

namespace ember::test {
namespace {

TEST(Process, CapMallocArenasDefersToTheEnvironment) {
  const char* before = std::getenv("MALLOC_ARENA_MAX");
  const std::string saved = before ? before : "";
  ASSERT_EQ(setenv("MALLOC_ARENA_MAX", "4", 1), 0);
  EXPECT_FALSE(cap_malloc_arenas());  // the user's setting stays
  if (before) {
    setenv("MALLOC_ARENA_MAX", saved.c_str(), 1);
  } else {
    unsetenv("MALLOC_ARENA_MAX");
  }
}

TEST(Process, CapMallocArenasAppliesToGlibcMallocOnly) {
  if (std::getenv("MALLOC_ARENA_MAX") || std::getenv("GLIBC_TUNABLES")) GTEST_SKIP() << "the environment chooses";
#if EMBER_GLIBC_MALLOC
  EXPECT_TRUE(cap_malloc_arenas(2));
#else  // another C library, or AddressSanitizer's allocator
  EXPECT_FALSE(cap_malloc_arenas(2));
#endif
}

}  // namespace
}  // namespace ember::test
