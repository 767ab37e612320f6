#include "pcsketch/core/allocator.h"

#include <gtest/gtest.h>

#include <cstdlib>
#include <cstring>

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

}  // namespace
}  // namespace pcsketch
