// `rfrecon selfcheck` as a library call: both entries of the self-check kernel on each device against C++.
#pragma once

#include <cstddef>
#include <vector>

#include "host/cl/device_context.h"
#include "host/cl/kernel_entry.h"

namespace rfrecon::selfcheck {

using cl::KernelEntry;

struct SelfcheckResult {
  const cl::DeviceInfo* device = nullptr;
  KernelEntry entry = KernelEntry::kNdRange;
  std::size_t elements = 0;
  std::size_t mismatches = 0;  // elements that differ from the C++ reference (bit for bit)
};

inline constexpr std::size_t kMaxSelfcheckElements = std::size_t{1} << 26;  // 64 M: 768 MiB of buffers

// Runs axpy over `elements` values (at most kMaxSelfcheckElements) with each entry on each device, in that order.

std::vector<SelfcheckResult> run_selfcheck(std::vector<cl::DeviceContext>& devices, std::size_t elements);

}  // namespace rfrecon::selfcheck
