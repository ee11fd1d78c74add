// glibc's mallopt: a fixed mmap threshold at its 64-bit maximum, and no trimming.
#include "host/core/freed_memory.h"

#include <climits>

#ifdef __GLIBC__
#include <malloc.h>
#endif

namespace rfrecon {

bool keep_freed_memory() {
#ifdef __GLIBC__
  constexpr int kLargestHeapBlock = 32 << 20;  // glibc's largest mmap threshold on 64-bit targets
  return mallopt(M_MMAP_THRESHOLD, kLargestHeapBlock) == 1 && mallopt(M_TRIM_THRESHOLD, INT_MAX) == 1;
#else
  return false;
#endif
}

}  // namespace rfrecon
