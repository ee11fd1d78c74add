// Reference and OpenCL implementations of the self-check kernel.
#include "host/selfcheck/axpy.h"

#include <cmath>
#include <stdexcept>

#include "host/cl/error.h"

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
  const auto n = static_cast<cl_uint>(x.size());
  const std::size_t bytes = x.size() * sizeof(float);
  cl_int status = CL_SUCCESS;
  ::cl::Buffer x_buffer(device.context(), CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, bytes, const_cast<float*>(x.data()),
                        &status);
  RF_CL_CHECK_CODE(status, "clCreateBuffer(x)");
  ::cl::Buffer y_buffer(device.context(), CL_MEM_READ_WRITE | CL_MEM_COPY_HOST_PTR, bytes, y.data(), &status);
  RF_CL_CHECK_CODE(status, "clCreateBuffer(y)");

  const bool single = entry == KernelEntry::kSingleWorkItem;
  ::cl::Kernel kernel(programs.get(device, "selfcheck/axpy.cl"), single ? "axpy_single" : "axpy_ndrange", &status);
  RF_CL_CHECK_CODE(status, "clCreateKernel");
  RF_CL_CHECK(kernel.setArg(0, a));
  RF_CL_CHECK(kernel.setArg(1, x_buffer));
  RF_CL_CHECK(kernel.setArg(2, y_buffer));
  RF_CL_CHECK(kernel.setArg(3, n));
  auto& queue = device.queue();
  if (single) {
    RF_CL_CHECK(queue.enqueueNDRangeKernel(kernel, ::cl::NullRange, ::cl::NDRange(1), ::cl::NDRange(1)));
  } else {
    RF_CL_CHECK(queue.enqueueNDRangeKernel(kernel, ::cl::NullRange, ::cl::NDRange(n), ::cl::NullRange));
  }
  RF_CL_CHECK(queue.enqueueReadBuffer(y_buffer, CL_TRUE, 0, bytes, y.data()));
  return y;
}

}  // namespace rfrecon::selfcheck
