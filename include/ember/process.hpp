#pragma once
// Process-wide memory setting for applications that run ember's Booleans on
// many threads. The library never calls this itself (it changes the whole
// process's allocator); the ember command-line tool and the benchmark runner
// call it first thing in main().
//
// Why: glibc's malloc gives each thread that allocates its own heap ("arena",
// up to 8 per core). A Boolean's worker threads allocate and free buffers of
// every size; what a worker frees stays in its own heap, where no other
// thread can reuse it, so peak memory grows with the thread count and with
// every further Boolean in the same process. Two arenas keep the peak close
// to the single-threaded one at no measurable cost in time, where one arena
// would serialize the workers' allocations (docs/design.md, "Memory and
// parallelism").
#include <cstdlib>
#include <cstring>

// AddressSanitizer replaces malloc, and its mallopt sets nothing.
#if defined(__SANITIZE_ADDRESS__)
#define EMBER_GLIBC_MALLOC 0
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define EMBER_GLIBC_MALLOC 0
#endif
#endif
#if !defined(EMBER_GLIBC_MALLOC) && defined(__GLIBC__)
#include <malloc.h>
#if defined(M_ARENA_MAX)
#define EMBER_GLIBC_MALLOC 1
#endif
#endif
#if !defined(EMBER_GLIBC_MALLOC)
#define EMBER_GLIBC_MALLOC 0
#endif

namespace ember {

/// True when the environment sets glibc's arena count itself, either as
/// MALLOC_ARENA_MAX or as the glibc.malloc.arena_max tunable.
inline bool environment_sets_malloc_arenas() {
  if (std::getenv("MALLOC_ARENA_MAX")) return true;
  const char* tunables = std::getenv("GLIBC_TUNABLES");
  return tunables && std::strstr(tunables, "glibc.malloc.arena_max") != nullptr;
}

/// Caps glibc's malloc arenas at `arenas` (at least 1) for this process,
/// unless the environment already chooses (MALLOC_ARENA_MAX, or
/// glibc.malloc.arena_max in GLIBC_TUNABLES): call it before starting
/// threads. Returns whether the cap was set; false for `arenas < 1` and with
/// other allocators (other C libraries, AddressSanitizer's), which are left
/// as they are. An allocator swapped in with LD_PRELOAD (jemalloc, tcmalloc)
/// is invisible here: the call then sets a glibc option nothing uses.
inline bool cap_malloc_arenas(int arenas = 2) {
#if EMBER_GLIBC_MALLOC
  if (arenas < 1 || environment_sets_malloc_arenas()) return false;
  return mallopt(M_ARENA_MAX, arenas) == 1;
#else
  (void)arenas;
  return false;
#endif
}

}  // namespace ember
