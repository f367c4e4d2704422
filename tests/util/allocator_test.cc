#include "ramap/util/allocator.h"

#include <gtest/gtest.h>

#include <cstdlib>
#include <cstring>

#if defined(__GLIBC__)
#include <malloc.h>
#endif

namespace ramap {
namespace {

#if defined(__GLIBC__)
// A freed block of a few MiB, the size translation averaging and BA free in every iteration,
// stays in the heap for the next allocation instead of going back to the kernel.
TEST(KeepFreedMemoryForReuse, AFreedBlockOfEightMebibytesStaysInTheHeap) {
  KeepFreedMemoryForReuse();
  constexpr size_t kBytes = size_t{8} << 20;
  const size_t mapped_before = mallinfo2().hblkhd;
  // volatile: the compiler may not drop an allocation whose address it cannot follow.
  void* volatile block = std::malloc(kBytes);
  ASSERT_NE(block, nullptr);
  std::memset(block, 1, kBytes);
  // Not a block of its own from mmap, which free would unmap.
  EXPECT_EQ(mallinfo2().hblkhd, mapped_before);
  std::free(block);
  EXPECT_GE(mallinfo2().fordblks, kBytes);
}
#endif

}  // namespace
}  // namespace ramap
