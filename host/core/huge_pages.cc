// madvise(MADV_HUGEPAGE) over the 2 MB-aligned interior of a range.
#include "host/core/huge_pages.h"

#include <cstdint>

#include <sys/mman.h>

namespace rfrecon {

void advise_huge_pages(void* data, std::size_t bytes) {
  constexpr std::uintptr_t kHugePage = std::uintptr_t{2} << 20;
  const auto begin = reinterpret_cast<std::uintptr_t>(data);
  const std::uintptr_t first = (begin + kHugePage - 1) & ~(kHugePage - 1);
  const std::uintptr_t last = (begin + bytes) & ~(kHugePage - 1);
  if (last > first) madvise(static_cast<char*>(data) + (first - begin), last - first, MADV_HUGEPAGE);
}

}  // namespace rfrecon
