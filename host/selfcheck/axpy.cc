// Reference and OpenCL implementations of the self-check kernel.
#include "host/selfcheck/axpy.h"

#include <cmath>
#include <stdexcept>

#include "host/cl/kernel_launch.h"

namespace rfrecon::selfcheck {

std::vector<float> axpy_reference(float a, const std::vector<float>& x, std::vector<float> y) {
  if (x.size() != y.size()) throw std::invalid_argument("axpy: x and y differ in size");
  for (std::size_t i = 0; i < x.size(); ++i) y[i] = std::fma(a, x[i], y[i]);
  return y;
}

std::vector<float> axpy_opencl(cl::DeviceContext& device, cl::ProgramCache& programs, KernelEntry entry, float a,
                               const std::vector<float>& x, std::vector<float> y) {
  if (x.size() != y.size()) throw std::invalid_argument("axpy: x and y differ in size");
  if (x.empty()) return y;
  const ::cl::Buffer x_buffer = cl::upload(device.context(), x);
  const ::cl::Buffer y_buffer = cl::upload(device.context(), y, CL_MEM_READ_WRITE);
  ::cl::Kernel kernel = cl::make_kernel(programs.get(device, "selfcheck/axpy.cl"), "axpy", entry);
  cl::set_args(kernel, a, x_buffer, y_buffer, static_cast<cl_uint>(x.size()));
  cl::enqueue_kernel(device.queue(), kernel, entry, x.size());
  return cl::download<float>(device.queue(), y_buffer, y.size());
}

}  // namespace rfrecon::selfcheck
