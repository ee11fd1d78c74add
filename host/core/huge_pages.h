// Large host arrays backed by transparent huge pages where the kernel offers them on request (madvise mode).
#pragma once

#include <cstddef>
#include <vector>

namespace rfrecon {

// Asks the kernel to back [data, data + bytes) with huge pages; a hint, silently ignored where unsupported.
void advise_huge_pages(void* data, std::size_t bytes);

// `values` made `count` copies of `value`, its storage first reserved and advised to use huge pages, so that the
// fill faults once per 2 MB instead of once per 4 KB.
template <typename T>
void assign_on_huge_pages(std::vector<T>& values, std::size_t count, const T& value) {
  values.clear();
  values.reserve(count);
  advise_huge_pages(values.data(), count * sizeof(T));
  values.assign(count, value);
}

}  // namespace rfrecon
