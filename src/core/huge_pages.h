// Large arrays on transparent huge pages.
//
// The per-frame stages read arrays indexed by progressive-mesh node (1M+ entries on the
// 1.1M-face knot) and by slot or face of the adapted mesh, mostly at scattered indices. With
// 4 KiB pages nearly every such read also misses the TLB, and in a virtual machine a page
// walk is itself several memory reads. On Linux, memory advised with MADV_HUGEPAGE is backed
// by 2 MiB pages where the kernel can (transparent huge pages in "madvise" mode, the usual
// setting; in "always" mode this changes nothing, in "never" it is ignored). Measured on the
// knot at T = 7 px² (docs/performance.md, "Huge pages for the adaptation's arrays"): the
// adapt stage of a frame takes 5-12% less, depending on the machine's state.
//
// HugePageAllocator gives allocations of kHugeMinBytes (one huge page) or more a 2 MiB-aligned
// block and advises it; smaller ones go to std::allocator as usual. The block is not rounded up:
// its tail, past the last whole huge page, stays on ordinary pages, so no memory is added.
// It is stateless: vectors that use it compare and swap like ordinary ones. The `lodline`
// program also puts every block of that size on huge pages (app/large_allocations.cpp, with
// advise()); this allocator gives the same to the library's hot arrays wherever it runs (the
// Python module, the tests and benchmarks, other programs).
#pragma once

#include <cstddef>
#include <memory>
#include <new>
#include <vector>

namespace lodline {

namespace huge_pages {
inline constexpr std::size_t kPageBytes = std::size_t{2} << 20;
inline constexpr std::size_t kHugeMinBytes = kPageBytes;
/// Marks [p, p + bytes) for transparent huge pages (madvise MADV_HUGEPAGE); a no-op where
/// the system has none.
void advise(void* p, std::size_t bytes) noexcept;
/// Allocates `bytes` 2 MiB-aligned and advises huge pages; throws std::bad_alloc on failure.
void* allocate(std::size_t bytes);
void deallocate(void* p, std::size_t bytes) noexcept;
}  // namespace huge_pages

template <class T>
struct HugePageAllocator {
  using value_type = T;
  HugePageAllocator() noexcept = default;
  template <class U>
  HugePageAllocator(const HugePageAllocator<U>&) noexcept {}

  T* allocate(std::size_t n) {
    if (n > static_cast<std::size_t>(-1) / sizeof(T)) throw std::bad_array_new_length();
    const std::size_t bytes = n * sizeof(T);
    if (bytes < huge_pages::kHugeMinBytes) return std::allocator<T>().allocate(n);
    return static_cast<T*>(huge_pages::allocate(bytes));
  }
  void deallocate(T* p, std::size_t n) noexcept {
    const std::size_t bytes = n * sizeof(T);
    if (bytes < huge_pages::kHugeMinBytes) {
      std::allocator<T>().deallocate(p, n);
      return;
    }
    huge_pages::deallocate(p, bytes);
  }
  template <class U>
  bool operator==(const HugePageAllocator<U>&) const noexcept {
    return true;
  }
};

/// A vector whose storage, once large, lies on huge pages (for the hot per-node, per-slot
/// and per-face arrays of the frame stages).
template <class T>
using HugeVector = std::vector<T, HugePageAllocator<T>>;

}  // namespace lodline
