// The primal and dual products of host/transport/spmv.h over several devices: output pixels cut into tiles, each
// tile's slice of T streamed to its device double-buffered. Each output pixel is summed by one work-item in the
// same order as on one device, so the images equal primal_opencl / dual_opencl bit for bit.
#pragma once

#include <vector>

#include "host/cl/device_context.h"
#include "host/cl/entry_choice.h"
#include "host/cl/program_cache.h"
#include "host/sched/scheduler.h"
#include "host/transport/spmv.h"

namespace rfrecon::transport {

struct ProductRun {
  std::vector<float> image;
  sched::RunReport report;
};

// options.stage left at its default becomes "primal" / "dual"; a granularity of 0 becomes 256 pixels; `entries`
// (a KernelEntry forces one on every device) replaces options.entries.
ProductRun primal_on_devices(std::vector<cl::DeviceContext>& devices, cl::ProgramCache& programs,
                             const cl::EntryChoice& entries, const transport::CompressedTransport& transport,
                             const std::vector<float>& light_p, sched::Options options = {});
ProductRun dual_on_devices(std::vector<cl::DeviceContext>& devices, cl::ProgramCache& programs,
                           const cl::EntryChoice& entries, const transport::TransposedTransport& transposed,
                           const std::vector<float>& light_c, sched::Options options = {});

}  // namespace rfrecon::transport
