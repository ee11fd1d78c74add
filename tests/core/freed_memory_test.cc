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

TEST(FreedMemoryTest, ABlockFreedAndAllocatedAgainFaultsNoPageIn) {
#if !RF_TEST_GLIBC_MALLOC
  GTEST_SKIP() << "malloc is not glibc's";
#endif
  ASSERT_TRUE(keep_freed_memory());
  constexpr std::size_t kBytes = std::size_t{16} << 20;  // 4096 pages of 4 KiB: glibc's default would map it anew
  const long first = faults_of_a_written_block(kBytes);
  const long second = faults_of_a_written_block(kBytes);
  EXPECT_GT(first, 0);  // the first time, the heap grows into new pages (counted once each at most)
  // The same pages again: a few faults at most (the allocator's own bookkeeping), against 4096 for new memory.
  EXPECT_LT(second, 64) << "first " << first;
}

}  // namespace
}  // namespace rfrecon
