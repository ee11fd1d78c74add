// Which entry of a kernel runs: one work-item per pixel or row (CPU, GPU) or a single work-item loop (FPGA). Which
// device runs which: host/cl/entry_choice.h.
#pragma once

namespace rfrecon::cl {

enum class KernelEntry { kNdRange, kSingleWorkItem };

}  // namespace rfrecon::cl
