#include "core/huge_pages.h"

#include <cstdlib>

#if defined(__linux__)
#include <sys/mman.h>
#endif

namespace lodline::huge_pages {

namespace {
std::size_t roundUp(std::size_t bytes) { return (bytes + kPageBytes - 1) / kPageBytes * kPageBytes; }
}  // namespace

void* allocate(std::size_t bytes) {
  const std::size_t size = roundUp(bytes);
  void* p = std::aligned_alloc(kPageBytes, size);
  if (!p) throw std::bad_alloc();
#if defined(__linux__) && defined(MADV_HUGEPAGE)
  // Advice only: where the kernel has no huge pages to give (or THP is off) this fails or is
  // ignored, and the memory stays on ordinary pages.
  (void)madvise(p, size, MADV_HUGEPAGE);
#endif
  return p;
}

void deallocate(void* p, std::size_t) noexcept { std::free(p); }

}  // namespace lodline::huge_pages
