// Large host arrays backed by transparent huge pages where the kernel offers them on request (madvise mode), and
// refilled on every core when they already have the size asked for.
#pragma once

#include <algorithm>
#include <cstddef>
#include <vector>

#include "host/core/parallel_rows.h"

namespace rfrecon {

// Asks the kernel to back [data, data + bytes) with huge pages; a hint, silently ignored where unsupported.
void advise_huge_pages(void* data, std::size_t bytes);

// `values` made `count` copies of `value`. An array of that size already (an earlier scan's, in memory the process
// holds) is filled on every core, in blocks of 1 MiB; otherwise its storage is first reserved and advised to
// use huge pages, so that the fill (one thread: a vector cannot grow without initialising) faults once per 2 MB
// instead of once per 4 KB.
template <typename T>
void assign_on_huge_pages(std::vector<T>& values, std::size_t count, const T& value) {
  if (values.size() == count) {
    constexpr std::size_t kBlock = (std::size_t{1} << 20) / sizeof(T);
    for_each_row(static_cast<int>((count + kBlock - 1) / kBlock), [&](int block) {
      const std::size_t begin = static_cast<std::size_t>(block) * kBlock;
      const std::size_t end = std::min(count, begin + kBlock);
      std::fill(values.begin() + static_cast<std::ptrdiff_t>(begin), values.begin() + static_cast<std::ptrdiff_t>(end),
                value);
    });
    return;
  }
  values.clear();
  values.reserve(count);
  advise_huge_pages(values.data(), count * sizeof(T));
  values.assign(count, value);
}

}  // namespace rfrecon
