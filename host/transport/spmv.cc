// Transpose (counting sort), C++ references and OpenCL runs of the primal and dual products.
#include "host/transport/spmv.h"

#include <stdexcept>

#include "host/cl/error.h"

namespace rfrecon::transport {

namespace {

void check_light(std::size_t got, std::size_t expected, const char* what) {
  if (got != expected) {
    throw std::invalid_argument(std::string(what) + ": light has " + std::to_string(got) + " values, expected " +
                                std::to_string(expected));
  }
}

template <typename T>
::cl::Buffer input_buffer(cl::DeviceContext& device, const std::vector<T>& host) {
  cl_int status = CL_SUCCESS;
  // A zero-sized buffer is invalid in OpenCL; keep one element for empty inputs (never read).
  std::vector<T> padded;
  const std::vector<T>& data = host.empty() ? (padded = std::vector<T>(1)) : host;
  ::cl::Buffer buffer(device.context(), CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, data.size() * sizeof(T),
                      const_cast<T*>(data.data()), &status);
  RF_CL_CHECK_CODE(status, "clCreateBuffer");
  return buffer;
}

template <typename... Args>
std::vector<float> run_spmv(cl::DeviceContext& device, cl::ProgramCache& programs, KernelEntry entry, const char* name,
                            std::size_t n, const Args&... args) {
  std::vector<float> image(n, 0.0f);
  if (n == 0) return image;
  const bool single = entry == KernelEntry::kSingleWorkItem;
  cl_int status = CL_SUCCESS;
  ::cl::Kernel kernel(programs.get(device, "transport/spmv.cl"),
                      (std::string(name) + (single ? "_single" : "_ndrange")).c_str(), &status);
  RF_CL_CHECK_CODE(status, "clCreateKernel");
  ::cl::Buffer output(device.context(), CL_MEM_WRITE_ONLY, n * sizeof(float), nullptr, &status);
  RF_CL_CHECK_CODE(status, "clCreateBuffer");
  cl_uint index = 0;
  (RF_CL_CHECK(kernel.setArg(index++, args)), ...);
  RF_CL_CHECK(kernel.setArg(index++, output));
  RF_CL_CHECK(kernel.setArg(index++, static_cast<cl_uint>(n)));
  RF_CL_CHECK(device.queue().enqueueNDRangeKernel(kernel, ::cl::NullRange, single ? ::cl::NDRange(1) : ::cl::NDRange(n),
                                                  single ? ::cl::NDRange(1) : ::cl::NullRange));
  RF_CL_CHECK(device.queue().enqueueReadBuffer(output, CL_TRUE, 0, n * sizeof(float), image.data()));
  return image;
}

}  // namespace

TransposedTransport transpose(const CompressedTransport& transport) {
  TransposedTransport transposed;
  transposed.projector_size = transport.setup.projector_size;
  transposed.row_start.assign(transport.projector_pixels() + 1, 0);
  for (const std::int32_t q : transport.indices) {
    if (q >= 0) ++transposed.row_start[static_cast<std::size_t>(q) + 1];
  }
  for (std::size_t q = 0; q < transport.projector_pixels(); ++q) {
    transposed.row_start[q + 1] += transposed.row_start[q];
  }
  const auto nonzeros = static_cast<std::size_t>(transposed.row_start.back());
  transposed.camera_pixel.resize(nonzeros);
  transposed.weights.resize(nonzeros);
  std::vector<std::int32_t> next(transposed.row_start.begin(), transposed.row_start.end() - 1);
  const auto k = static_cast<std::size_t>(transport.k());
  for (std::size_t slot = 0; slot < transport.indices.size(); ++slot) {
    const std::int32_t q = transport.indices[slot];
    if (q < 0) continue;
    const auto j = static_cast<std::size_t>(next[static_cast<std::size_t>(q)]++);
    transposed.camera_pixel[j] = static_cast<std::int32_t>(slot / k);
    transposed.weights[j] = transport.weights[slot];
  }
  return transposed;
}

std::vector<float> primal_reference(const CompressedTransport& transport, const std::vector<float>& light_p) {
  check_light(light_p.size(), transport.projector_pixels(), "primal");
  std::vector<float> image(transport.camera_pixels(), 0.0f);
  const auto k = static_cast<std::size_t>(transport.k());
  for (std::size_t slot = 0; slot < transport.indices.size(); ++slot) {
    const std::int32_t q = transport.indices[slot];
    if (q >= 0) image[slot / k] += transport.weights[slot] * light_p[static_cast<std::size_t>(q)];
  }
  return image;
}

std::vector<float> dual_reference(const CompressedTransport& transport, const std::vector<float>& light_c) {
  check_light(light_c.size(), transport.camera_pixels(), "dual");
  std::vector<float> image(transport.projector_pixels(), 0.0f);
  const auto k = static_cast<std::size_t>(transport.k());
  for (std::size_t slot = 0; slot < transport.indices.size(); ++slot) {
    const std::int32_t q = transport.indices[slot];
    if (q >= 0) image[static_cast<std::size_t>(q)] += transport.weights[slot] * light_c[slot / k];
  }
  return image;
}

std::vector<float> primal_opencl(cl::DeviceContext& device, cl::ProgramCache& programs, KernelEntry entry,
                                 const CompressedTransport& transport, const std::vector<float>& light_p) {
  check_light(light_p.size(), transport.projector_pixels(), "primal");
  return run_spmv(device, programs, entry, "primal", transport.camera_pixels(), static_cast<cl_uint>(transport.k()),
                  input_buffer(device, transport.indices), input_buffer(device, transport.weights),
                  input_buffer(device, light_p));
}

std::vector<float> dual_opencl(cl::DeviceContext& device, cl::ProgramCache& programs, KernelEntry entry,
                               const TransposedTransport& transposed, const std::vector<float>& light_c) {
  const std::size_t n = static_cast<std::size_t>(transposed.projector_size.area());
  if (transposed.row_start.size() != n + 1) throw std::invalid_argument("dual: malformed transposed transport");
  return run_spmv(device, programs, entry, "dual", n, input_buffer(device, transposed.row_start),
                  input_buffer(device, transposed.camera_pixel), input_buffer(device, transposed.weights),
                  input_buffer(device, light_c));
}

}  // namespace rfrecon::transport
