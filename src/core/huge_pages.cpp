#include "core/huge_pages.h"

#include <cstdlib>

#if defined(__linux__)
#include <sys/mman.h>
#endif

namespace lodline::huge_pages {

void advise(void* p, std::size_t bytes) noexcept {
#if defined(__linux__) && defined(MADV_HUGEPAGE)
  // Advice only: where the kernel has no huge pages to give (or THP is off) this fails or is
  // ignored, and the memory stays on ordinary pages.
  (void)madvise(p, bytes, MADV_HUGEPAGE);
#else
  (void)p;
  (void)bytes;
#endif
}

void* allocate(std::size_t bytes) {
  void* p = nullptr;
  if (posix_memalign(&p, kPageBytes, bytes) != 0) throw std::bad_alloc();
  advise(p, bytes);
  return p;
}

void deallocate(void* p, std::size_t) noexcept { std::free(p); }

}  // namespace lodline::huge_pages
