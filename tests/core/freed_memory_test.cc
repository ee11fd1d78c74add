// After keep_freed_memory, a block freed and allocated again is the same memory: touching it again faults no page in.
#include "host/core/freed_memory.h"

#include <cstddef>
#include <cstring>
#include <memory>

#include <gtest/gtest.h>
#include <sys/resource.h>

// AddressSanitizer's allocator replaces glibc's malloc (its mallopt changes nothing).
#if defined(__SANITIZE_ADDRESS__)
#define RF_TEST_GLIBC_MALLOC 0
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define RF_TEST_GLIBC_MALLOC 0
#endif
#endif
#if !defined(RF_TEST_GLIBC_MALLOC) && defined(__GLIBC__)
#define RF_TEST_GLIBC_MALLOC 1
#elif !defined(RF_TEST_GLIBC_MALLOC)
#define RF_TEST_GLIBC_MALLOC 0
#endif

namespace rfrecon {
namespace {

long minor_faults() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return usage.ru_minflt;
}

// Allocates `bytes`, writes every byte and frees them; returns the minor page faults this took.
long faults_of_a_written_block(std::size_t bytes) {
  const long before = minor_faults();
  const std::unique_ptr<char[]> block(new char[bytes]);
  std::memset(block.get(), 1, bytes);
  asm volatile("" : : "r"(block.get()) : "memory");  // the writes are kept: the block escapes
  return minor_faults() - before;
}

// 16 MiB: glibc's default would map it anew each time; 48 MiB: more than glibc's largest mmap threshold (32 MiB), as
// a 4096 x 2730 camera's float image (45 MB).
class FreedMemoryTest : public ::testing::TestWithParam<std::size_t> {};

TEST_P(FreedMemoryTest, ABlockFreedAndAllocatedAgainFaultsNoPageIn) {
#if !RF_TEST_GLIBC_MALLOC
  GTEST_SKIP() << "malloc is not glibc's";
#endif
  ASSERT_TRUE(keep_freed_memory());
  const std::size_t bytes = GetParam() << 20;
  const long first = faults_of_a_written_block(bytes);
  const long second = faults_of_a_written_block(bytes);
  // The first time, the heap grows into new pages (counted once each at most: 4096 per 16 MiB).
  EXPECT_GT(first, 0);
  // The same pages again: a few faults at most (the allocator's own bookkeeping).
  EXPECT_LT(second, 64) << "first " << first;
}

INSTANTIATE_TEST_SUITE_P(MiB, FreedMemoryTest, ::testing::Values(std::size_t{16}, std::size_t{48}));

}  // namespace
}  // namespace rfrecon
