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

// Worked out here, independently of process.hpp's EMBER_GLIBC_MALLOC: glibc's
// own malloc is in use unless AddressSanitizer replaced it.
#if defined(__SANITIZE_ADDRESS__)
constexpr bool kAsan = true;
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
constexpr bool kAsan = true;
#else
constexpr bool kAsan = false;
#endif
#else
constexpr bool kAsan = false;
#endif
#if defined(__GLIBC__)
constexpr bool kGlibcMalloc = !kAsan;
#else
constexpr bool kGlibcMalloc = false;
#endif

TEST(Process, CapMallocArenasAppliesToGlibcMallocOnly) {
  if (environment_sets_malloc_arenas()) GTEST_SKIP() << "the environment chooses";
  EXPECT_EQ(cap_malloc_arenas(2), kGlibcMalloc);
}

TEST(Process, CapMallocArenasRefusesFewerThanOneArena) {
  EXPECT_FALSE(cap_malloc_arenas(0));
  EXPECT_FALSE(cap_malloc_arenas(-3));
}

TEST(Process, OnlyTheArenaTunableCountsAsTheEnvironmentsChoice) {
  if (std::getenv("MALLOC_ARENA_MAX")) GTEST_SKIP() << "MALLOC_ARENA_MAX is set";
  const char* before = std::getenv("GLIBC_TUNABLES");
  const std::string saved = before ? before : "";
  ASSERT_EQ(setenv("GLIBC_TUNABLES", "glibc.malloc.tcache_count=0", 1), 0);
  EXPECT_FALSE(environment_sets_malloc_arenas());
  ASSERT_EQ(setenv("GLIBC_TUNABLES", "glibc.malloc.tcache_count=0:glibc.malloc.arena_max=3", 1), 0);
  EXPECT_TRUE(environment_sets_malloc_arenas());
  EXPECT_FALSE(cap_malloc_arenas());
  if (before) {
    setenv("GLIBC_TUNABLES", saved.c_str(), 1);
  } else {
    unsetenv("GLIBC_TUNABLES");
  }
}

}  // namespace
}  // namespace ember::test
