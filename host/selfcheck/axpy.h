// The self-check computation y = a x + y: the C++ reference and its OpenCL run on one device.
#pragma once

#include <vector>

#include "host/cl/device_context.h"
#include "host/cl/kernel_entry.h"
#include "host/cl/program_cache.h"

namespace rfrecon::selfcheck {

using cl::KernelEntry;

// Plain C++ reference: y[i] = fma(a, x[i], y[i]).
std::vector<float> axpy_reference(float a, const std::vector<float>& x, std::vector<float> y);

// The same on `device` with kernels/selfcheck/axpy.cl, through the chosen entry.
std::vector<float> axpy_opencl(cl::DeviceContext& device, cl::ProgramCache& programs, KernelEntry entry, float a,
                               const std::vector<float>& x, std::vector<float> y);

}  // namespace rfrecon::selfcheck
