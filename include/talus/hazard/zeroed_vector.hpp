// ZeroedVector: storage for the per-cell arrays of the statistical map (docs/architecture.md section 2,
// "Statistical maps"), which start at zero and are written only where trajectories pass. The
// memory comes from calloc and value-initialisation writes nothing, so on systems that hand out
// large blocks as untouched zero pages (Linux, via mmap) a per-cell array occupies memory only
// for the pages that hold written cells: memory follows the area the rocks reach, not the DEM.
// Only for arrays of numbers sized once at construction: growing a shrunk vector would not
// re-zero its elements.
#pragma once

#include <cstddef>
#include <cstdlib>
#include <new>
#include <type_traits>
#include <utility>
#include <vector>

namespace talus {

template <class T>
struct ZeroedAllocator {
  static_assert(std::is_arithmetic_v<T>, "all-zero bytes must be the value 0");
  using value_type = T;

  ZeroedAllocator() = default;
  template <class U>
  explicit ZeroedAllocator(const ZeroedAllocator<U>&) noexcept {}

  T* allocate(std::size_t n) {
    void* memory = std::calloc(n, sizeof(T));
    if (memory == nullptr) throw std::bad_alloc();
    return static_cast<T*>(memory);
  }
  void deallocate(T* memory, std::size_t) noexcept { std::free(memory); }

  template <class U>
  void construct(U*) noexcept {}   // value-initialisation: calloc's zeros already are the value
  template <class U, class... Args>
  void construct(U* p, Args&&... args) {
    ::new (static_cast<void*>(p)) U(std::forward<Args>(args)...);
  }

  friend bool operator==(const ZeroedAllocator&, const ZeroedAllocator&) { return true; }
};

template <class T>
using ZeroedVector = std::vector<T, ZeroedAllocator<T>>;

}  // namespace talus
