// glibc's mallopt: no block mapped on its own, and no trimming.
#include "host/core/freed_memory.h"

#include <climits>

#ifdef __GLIBC__
#include <malloc.h>
#endif

namespace rfrecon {

bool keep_freed_memory() {
#ifdef __GLIBC__
  return mallopt(M_MMAP_MAX, 0) == 1 && mallopt(M_TRIM_THRESHOLD, INT_MAX) == 1;
#else
  return false;
#endif
}

}  // namespace rfrecon
