#include "core/huge_pages.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <numeric>
#include <sstream>
#include <string>

namespace lodline {
namespace {

// The VmFlags line of the mapping in /proc/self/smaps that contains `p` ("" if none).
std::string vmFlagsAt(const void* p) {
  std::ifstream smaps("/proc/self/smaps");
  const auto addr = reinterpret_cast<uintptr_t>(p);
  std::string line;
  bool inside = false;
  while (std::getline(smaps, line)) {
    uintptr_t lo = 0, hi = 0;
    char dash = 0;
    std::istringstream head(line);
    if (head >> std::hex >> lo >> dash >> hi && dash == '-') {
      inside = lo <= addr && addr < hi;
      continue;
    }
    if (inside && line.rfind("VmFlags:", 0) == 0) return line;
  }
  return "";
}

TEST(HugePages, SmallArraysAreOrdinaryAndLargeOnesAreAlignedAndKeepTheirContents) {
  HugeVector<uint32_t> small(1000);
  std::iota(small.begin(), small.end(), 0u);
  EXPECT_EQ(small[999], 999u);

  // Grown past the threshold by push_back: every reallocation keeps the contents.
  HugeVector<uint32_t> v;
  const size_t n = 3 * huge_pages::kHugeMinBytes / sizeof(uint32_t);
  for (uint32_t i = 0; i < n; ++i) v.push_back(i * 7u);
  ASSERT_GE(v.capacity() * sizeof(uint32_t), huge_pages::kHugeMinBytes);
  EXPECT_EQ(reinterpret_cast<uintptr_t>(v.data()) % huge_pages::kPageBytes, 0u);
  bool same = true;
  for (uint32_t i = 0; i < n; ++i) same = same && v[i] == i * 7u;
  EXPECT_TRUE(same);

  // Vectors with this allocator copy, move and swap like ordinary ones.
  HugeVector<uint32_t> copy = v;
  EXPECT_EQ(copy, v);
  HugeVector<uint32_t> moved = std::move(copy);
  moved.swap(small);
  EXPECT_EQ(small, v);
  EXPECT_EQ(moved.size(), 1000u);
}

TEST(HugePages, LargeArraysAreAdvised) {
  // Where the kernel has transparent huge pages, the advice shows as "hg" in the mapping's
  // flags, whether or not a huge page was free to back it.
  if (!std::filesystem::exists("/sys/kernel/mm/transparent_hugepage/enabled") ||
      !std::filesystem::exists("/proc/self/smaps"))
    GTEST_SKIP() << "no transparent huge pages here";
  // An ordinary vector of the same size first: if it shows the flag too, the whole heap is
  // advised (GLIBC_TUNABLES=glibc.malloc.hugetlb=1, say) and the check proves nothing.
  std::vector<float> plain(huge_pages::kHugeMinBytes / sizeof(float) + 1, 1.0f);
  const std::string plain_flags = vmFlagsAt(plain.data());
  ASSERT_FALSE(plain_flags.empty());
  if (plain_flags.find(" hg") != std::string::npos) GTEST_SKIP() << "the heap is advised already";
  HugeVector<float> v(plain.size(), 1.0f);
  const std::string flags = vmFlagsAt(v.data());
  ASSERT_FALSE(flags.empty());
  EXPECT_NE(flags.find(" hg"), std::string::npos) << flags;
}

}  // namespace
}  // namespace lodline
