// The program's global operator new: blocks of 2 MiB and more are aligned to 2 MiB and
// marked for transparent huge pages (madvise MADV_HUGEPAGE; Debian's kernels enable THP "on
// madvise" by default), the rest is plain malloc. A million-face model allocates a few
// hundred MB of flat arrays at load (mesh, progressive mesh, the adaptive mesh's per-node
// records, the hierarchy check's face records); on 4 KiB pages every first touch of a page
// is a fault, and those faults were a third of a detail-controlled `lodline render` of a
// 1.1M-face model (docs/performance.md, "Loading a cached progressive mesh"). With huge
// pages the same arrays take ~14× fewer faults and fewer TLB misses when the adaptation and
// the hierarchy check visit them out of order.
//
// Linked into the `lodline` executable only (not the library, the tests' binaries or the
// Python module), and left out of sanitizer builds, whose allocators must see every block.
// Where THP is off, madvise fails harmlessly and the blocks are ordinary memory. The
// library's hot arrays get the same on their own (core/huge_pages.h).
#include <algorithm>
#include <cstddef>
#include <cstdlib>
#include <new>

#include "core/huge_pages.h"

namespace {

constexpr std::size_t kHugePage = lodline::huge_pages::kPageBytes;

void* allocate(std::size_t size, std::size_t align) noexcept {
  if (size == 0) size = 1;
  if (size >= kHugePage) {
    void* p = nullptr;
    if (posix_memalign(&p, std::max(align, kHugePage), size) != 0) return nullptr;
    lodline::huge_pages::advise(p, size);  // advice only: an error leaves ordinary pages
    return p;
  }
  if (align <= alignof(std::max_align_t)) return std::malloc(size);
  void* p = nullptr;
  return posix_memalign(&p, std::max(align, sizeof(void*)), size) == 0 ? p : nullptr;
}

void* allocateOrThrow(std::size_t size, std::size_t align) {
  for (;;) {
    if (void* p = allocate(size, align)) return p;
    std::new_handler handler = std::get_new_handler();
    if (!handler) throw std::bad_alloc();
    handler();
  }
}

void* allocateOrNull(std::size_t size, std::size_t align) noexcept {
  try {
    return allocateOrThrow(size, align);
  } catch (...) {
    return nullptr;
  }
}

constexpr std::size_t kDefault = __STDCPP_DEFAULT_NEW_ALIGNMENT__;

}  // namespace

void* operator new(std::size_t n) { return allocateOrThrow(n, kDefault); }
void* operator new[](std::size_t n) { return allocateOrThrow(n, kDefault); }
void* operator new(std::size_t n, std::align_val_t a) { return allocateOrThrow(n, static_cast<std::size_t>(a)); }
void* operator new[](std::size_t n, std::align_val_t a) { return allocateOrThrow(n, static_cast<std::size_t>(a)); }
void* operator new(std::size_t n, const std::nothrow_t&) noexcept { return allocateOrNull(n, kDefault); }
void* operator new[](std::size_t n, const std::nothrow_t&) noexcept { return allocateOrNull(n, kDefault); }
void* operator new(std::size_t n, std::align_val_t a, const std::nothrow_t&) noexcept {
  return allocateOrNull(n, static_cast<std::size_t>(a));
}
void* operator new[](std::size_t n, std::align_val_t a, const std::nothrow_t&) noexcept {
  return allocateOrNull(n, static_cast<std::size_t>(a));
}

// Every block above came from malloc or posix_memalign: free releases each.
void operator delete(void* p) noexcept { std::free(p); }
void operator delete[](void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }
void operator delete[](void* p, std::size_t) noexcept { std::free(p); }
void operator delete(void* p, std::align_val_t) noexcept { std::free(p); }
void operator delete[](void* p, std::align_val_t) noexcept { std::free(p); }
void operator delete(void* p, std::size_t, std::align_val_t) noexcept { std::free(p); }
void operator delete[](void* p, std::size_t, std::align_val_t) noexcept { std::free(p); }
void operator delete(void* p, const std::nothrow_t&) noexcept { std::free(p); }
void operator delete[](void* p, const std::nothrow_t&) noexcept { std::free(p); }
void operator delete(void* p, std::align_val_t, const std::nothrow_t&) noexcept { std::free(p); }
void operator delete[](void* p, std::align_val_t, const std::nothrow_t&) noexcept { std::free(p); }
