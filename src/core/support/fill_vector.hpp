#pragma once
// Vectors whose resize leaves new elements unwritten, for large buffers that a
// parallel loop then fills completely.
//
// std::vector<T>(n) value-initializes: one serial pass that zeroes every byte
// and takes every page fault of fresh memory before the parallel fill writes
// the same bytes again: a serial pass over every large buffer, in which the
// other threads wait. With FillVector the fill is the first touch, in
// parallel.
//
// Only for implicit-lifetime element types (here: trivially copy-
// constructible and destructible, such as IntPoint arrays and std::pair of
// integers): allocating their storage creates the objects (C++20, P0593), so
// skipping construction is well defined; reading an element before the fill
// wrote it is not. Other constructors (copies, values,
// initializer lists) behave as in std::vector.
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <cstddef>
#include <memory>
#include <type_traits>
#include <utility>
#include <vector>

namespace ember::core {

template <typename T>
class NoInitAllocator : public std::allocator<T> {
 public:
  using value_type = T;
  template <typename U>
  struct rebind {
    using other = NoInitAllocator<U>;
  };
  NoInitAllocator() noexcept = default;
  template <typename U>
  NoInitAllocator(const NoInitAllocator<U>&) noexcept {}

  /// The value-less construction that resize() uses: nothing.
  template <typename U>
  void construct(U*) noexcept {
    static_assert(std::is_trivially_copy_constructible_v<U> && std::is_trivially_destructible_v<U>,
                  "FillVector: elements must be implicit-lifetime types");
  }
  template <typename U, typename... Args>
  void construct(U* p, Args&&... args) {
    ::new (static_cast<void*>(p)) U(std::forward<Args>(args)...);
  }
  template <typename U>
  friend bool operator==(const NoInitAllocator<T>&, const NoInitAllocator<U>&) noexcept {
    return true;
  }
};

template <typename T>
using FillVector = std::vector<T, NoInitAllocator<T>>;

/// Reserves room for n elements of v and takes the page faults of the fresh
/// storage in parallel, one write per page, before a resize that must
/// construct its elements one by one (types that are not implicit-lifetime,
/// such as the soup's polygons with their unique_ptr). The root soup of a
/// large input is tens of megabytes, whose page faults, taken serially by
/// the resize, would be a large part of the set-up; on mapped pages the
/// construction runs at memory speed. The writes go to bytes of the allocation that no
/// element occupies yet (the resize then constructs over them). Address-
/// sanitized builds skip them: a vector's unused capacity may be poisoned
/// there (libc++, or libstdc++ with _GLIBCXX_SANITIZE_VECTOR), and the touch
/// only saves time.
template <typename T, typename A>
void reserve_touched(std::vector<T, A>& v, std::size_t n) {
  if (n <= v.size()) return;
  v.reserve(n);
#if defined(__SANITIZE_ADDRESS__)
  return;
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
  return;
#endif
#endif
  unsigned char* const fresh = reinterpret_cast<unsigned char*>(v.data()) + v.size() * sizeof(T);
  const std::size_t bytes = (n - v.size()) * sizeof(T);
  constexpr std::size_t kPage = 4096;
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, (bytes + kPage - 1) / kPage, 64),
                    [&](const tbb::blocked_range<std::size_t>& r) {
                      for (std::size_t page = r.begin(); page != r.end(); ++page) fresh[page * kPage] = 0;
                    });
}

}  // namespace ember::core
