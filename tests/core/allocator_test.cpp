#include "pcsketch/core/allocator.h"

#include <gtest/gtest.h>

#include <cstdlib>
#include <cstring>
#include <string>

#if defined(__GLIBC__)
#include <malloc.h>
#endif

namespace pcsketch {
namespace {

#if defined(__GLIBC__) && !defined(__SANITIZE_ADDRESS__)
// A 64 MiB block (a 1M-point cloud's neighbour lists) comes from the heap, not from its own mapping, and freeing it
// leaves the memory with the allocator for the next stage.
TEST(Allocator, LargeBlocksComeFromTheHeapAndStayAfterFree) {
  keep_freed_memory();
  const std::size_t bytes = std::size_t{64} << 20;
  const std::size_t mapped_before = mallinfo2().hblkhd;
  void* block = std::malloc(bytes);
  ASSERT_NE(block, nullptr);
  std::memset(block, 1, bytes);
  EXPECT_EQ(mallinfo2().hblkhd, mapped_before);  // no new mapping
  std::free(block);
  EXPECT_GE(mallinfo2().fordblks, bytes);  // kept as free heap memory, not trimmed
}
#else
TEST(Allocator, LargeBlocksComeFromTheHeapAndStayAfterFree) {
  GTEST_SKIP() << "glibc's malloc only (the sanitizers bring their own allocator)";
}
#endif

// The tunable is added after what the user set, and never twice nor over the user's own choice.
TEST(Allocator, HugePageTunableIsAddedOnce) {
  EXPECT_EQ(detail::huge_page_tunables(nullptr), "glibc.malloc.hugetlb=1");
  EXPECT_EQ(detail::huge_page_tunables(""), "glibc.malloc.hugetlb=1");
  EXPECT_EQ(detail::huge_page_tunables("glibc.malloc.check=0"), "glibc.malloc.check=0:glibc.malloc.hugetlb=1");
  EXPECT_EQ(detail::huge_page_tunables("glibc.malloc.hugetlb=0"), "");
  EXPECT_EQ(detail::huge_page_tunables("glibc.malloc.hugetlb=1:glibc.malloc.check=0"), "");
}

// With the tunable set (as after the restart), the call returns: a program that calls it first never loops.
TEST(Allocator, RestartReturnsOnceTheTunableIsSet) {
  const char* before = std::getenv("GLIBC_TUNABLES");
  const std::string saved = before ? before : "";
  ASSERT_EQ(setenv("GLIBC_TUNABLES", "glibc.malloc.hugetlb=0", 1), 0);
  char name[] = "allocator_test";
  char* argv[] = {name, nullptr};
  restart_with_huge_pages(argv);
  EXPECT_STREQ(std::getenv("GLIBC_TUNABLES"), "glibc.malloc.hugetlb=0");
  if (before)
    setenv("GLIBC_TUNABLES", saved.c_str(), 1);
  else
    unsetenv("GLIBC_TUNABLES");
}

}  // namespace
}  // namespace pcsketch
