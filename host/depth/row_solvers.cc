// Plain C++ and OpenCL drivers of the row solvers; the per-row arithmetic is shared with the kernels through
// kernels/depth/row_integration.h and row_fusion.h.
#include "host/depth/row_solvers.h"

#include <initializer_list>
#include <limits>
#include <stdexcept>
#include <string>

#include "host/cl/error.h"
#include "kernels/depth/row_fusion.h"
#include "kernels/depth/row_integration.h"

namespace rfrecon::depth {

namespace {

void check_range(const RectifiedRows& rows, int row_begin, int row_end) {
  if (row_begin < 0 || row_end > rows.height || row_begin >= row_end) {
    throw std::invalid_argument("row range [" + std::to_string(row_begin) + ", " + std::to_string(row_end) +
                                ") is empty or outside the " + std::to_string(rows.height) + " rectified rows");
  }
  if (rows.e_cam.size() != rows.pixels() || rows.z_tri.size() != rows.pixels() || rows.runs.size() != rows.pixels() ||
      rows.e_proj.size() != static_cast<std::size_t>(rows.height) * static_cast<std::size_t>(rows.proj_width)) {
    throw std::invalid_argument("rectified rows: buffer sizes do not match the image sizes");
  }
}

void check_options(const IntegrationOptions& options) {
  if (options.passes < 1) throw std::invalid_argument("integration: passes must be >= 1");
}

void check_options(const FusionOptions& options) {
  if (options.iterations < 1 || !(options.sigma_disparity_px > 0.0f) || !(options.sigma_step_mm > 0.0f)) {
    throw std::invalid_argument("fusion: iterations must be >= 1 and both sigmas > 0");
  }
}

std::size_t offset(const RectifiedRows& rows, int row) {
  return static_cast<std::size_t>(row) * static_cast<std::size_t>(rows.width);
}

// The fusion's arguments checked; returns a copy of the starting depth to refine.
std::vector<float> checked_fusion_start(const RectifiedRows& rows, const std::vector<float>& z_start,
                                        const FusionOptions& options, int row_begin, int row_end) {
  check_range(rows, row_begin, row_end);
  check_options(options);
  if (z_start.size() != offset(rows, row_end) - offset(rows, row_begin)) {
    throw std::invalid_argument("fusion: the starting depth does not cover the row range");
  }
  return z_start;
}

std::size_t proj_offset(const RectifiedRows& rows, int row) {
  return static_cast<std::size_t>(row) * static_cast<std::size_t>(rows.proj_width);
}

// Device buffers of the inputs for rows [row_begin, row_end).
struct RowBuffers {
  ::cl::Buffer e_cam, e_proj, z_tri, runs;

  RowBuffers(cl::DeviceContext& device, const RectifiedRows& rows, int row_begin, int row_end) {
    const std::size_t pixels = offset(rows, row_end) - offset(rows, row_begin);
    const std::size_t proj_pixels = proj_offset(rows, row_end) - proj_offset(rows, row_begin);
    e_cam = make(device, rows.e_cam.data() + offset(rows, row_begin), pixels * sizeof(float), "clCreateBuffer(e_cam)");
    e_proj = make(device, rows.e_proj.data() + proj_offset(rows, row_begin), proj_pixels * sizeof(float),
                  "clCreateBuffer(e_proj)");
    z_tri = make(device, rows.z_tri.data() + offset(rows, row_begin), pixels * sizeof(float), "clCreateBuffer(z_tri)");
    runs = make(device, rows.runs.data() + offset(rows, row_begin), pixels, "clCreateBuffer(runs)");
  }

  static ::cl::Buffer make(cl::DeviceContext& device, const void* data, std::size_t bytes, const char* name) {
    cl_int status = CL_SUCCESS;
    ::cl::Buffer buffer(device.context(), CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, bytes, const_cast<void*>(data),
                        &status);
    RF_CL_CHECK_CODE(status, name);
    return buffer;
  }
};

// Sets the arguments shared by both kernels (geometry, tile, sizes) and returns the next argument index.
cl_uint set_common_args(::cl::Kernel& kernel, const RectifiedRows& rows, int row_begin, int row_end, int count) {
  cl_uint index = 0;
  for (const float value : {rows.rig.f, rows.rig.cx_cam, rows.rig.cx_proj, rows.rig.cy, rows.rig.b}) {
    RF_CL_CHECK(kernel.setArg(index++, value));
  }
  for (const cl_int value : {row_begin, row_end - row_begin, rows.width, rows.proj_width, count}) {
    RF_CL_CHECK(kernel.setArg(index++, value));
  }
  return index;
}

void run_rows(cl::DeviceContext& device, ::cl::Kernel& kernel, KernelEntry entry, int row_count) {
  const std::size_t global = entry == KernelEntry::kSingleWorkItem ? 1 : static_cast<std::size_t>(row_count);
  RF_CL_CHECK(
      device.queue().enqueueNDRangeKernel(kernel, ::cl::NullRange, ::cl::NDRange(global),
                                          entry == KernelEntry::kSingleWorkItem ? ::cl::NDRange(1) : ::cl::NullRange));
}

}  // namespace

std::vector<float> integrate_rows_reference(const RectifiedRows& rows, const IntegrationOptions& options, int row_begin,
                                            int row_end) {
  check_range(rows, row_begin, row_end);
  check_options(options);
  std::vector<float> z(offset(rows, row_end) - offset(rows, row_begin));
  for (int row = row_begin; row < row_end; ++row) {
    rf_integrate_row(rows.rig, rows.beta(row), rows.width, rows.proj_width, options.passes,
                     rows.e_cam.data() + offset(rows, row), rows.e_proj.data() + proj_offset(rows, row),
                     rows.z_tri.data() + offset(rows, row), rows.runs.data() + offset(rows, row),
                     z.data() + offset(rows, row - row_begin));
  }
  return z;
}

std::vector<float> fuse_rows_reference(const RectifiedRows& rows, const std::vector<float>& z_start,
                                       const FusionOptions& options, int row_begin, int row_end) {
  std::vector<float> z = checked_fusion_start(rows, z_start, options, row_begin, row_end);
  std::vector<float> c(static_cast<std::size_t>(rows.width)), d(c.size());
  for (int row = row_begin; row < row_end; ++row) {
    rf_fuse_row(rows.rig, rows.beta(row), rows.width, rows.proj_width, options.iterations, options.sigma_disparity_px,
                options.sigma_step_mm, rows.e_cam.data() + offset(rows, row),
                rows.e_proj.data() + proj_offset(rows, row), rows.z_tri.data() + offset(rows, row),
                rows.runs.data() + offset(rows, row), z.data() + offset(rows, row - row_begin), c.data(), d.data());
  }
  return z;
}

std::vector<float> integrate_rows_opencl(cl::DeviceContext& device, cl::ProgramCache& programs, KernelEntry entry,
                                         const RectifiedRows& rows, const IntegrationOptions& options, int row_begin,
                                         int row_end) {
  check_range(rows, row_begin, row_end);
  check_options(options);
  const RowBuffers inputs(device, rows, row_begin, row_end);
  // z also holds each run's seed between passes. It starts defined (NaN) because the compiler may load z and z_tri
  // both before choosing the seed of the first pass (oclgrind reports that load otherwise).
  std::vector<float> z(offset(rows, row_end) - offset(rows, row_begin), std::numeric_limits<float>::quiet_NaN());
  cl_int status = CL_SUCCESS;
  ::cl::Buffer z_buffer(device.context(), CL_MEM_READ_WRITE | CL_MEM_COPY_HOST_PTR, z.size() * sizeof(float), z.data(),
                        &status);
  RF_CL_CHECK_CODE(status, "clCreateBuffer(z)");
  const bool single = entry == KernelEntry::kSingleWorkItem;
  ::cl::Kernel kernel(programs.get(device, "depth/integrate.cl"),
                      single ? "integrate_rows_single" : "integrate_rows_ndrange", &status);
  RF_CL_CHECK_CODE(status, "clCreateKernel(integrate_rows)");
  cl_uint index = set_common_args(kernel, rows, row_begin, row_end, options.passes);
  for (const ::cl::Buffer* buffer : std::initializer_list<const ::cl::Buffer*>{
           &inputs.e_cam, &inputs.e_proj, &inputs.z_tri, &inputs.runs, &z_buffer}) {
    RF_CL_CHECK(kernel.setArg(index++, *buffer));
  }
  run_rows(device, kernel, entry, row_end - row_begin);
  RF_CL_CHECK(device.queue().enqueueReadBuffer(z_buffer, CL_TRUE, 0, z.size() * sizeof(float), z.data()));
  return z;
}

std::vector<float> fuse_rows_opencl(cl::DeviceContext& device, cl::ProgramCache& programs, KernelEntry entry,
                                    const RectifiedRows& rows, const std::vector<float>& z_start,
                                    const FusionOptions& options, int row_begin, int row_end) {
  std::vector<float> z = checked_fusion_start(rows, z_start, options, row_begin, row_end);
  const RowBuffers inputs(device, rows, row_begin, row_end);
  const std::size_t bytes = z.size() * sizeof(float);
  cl_int status = CL_SUCCESS;
  ::cl::Buffer z_buffer(device.context(), CL_MEM_READ_WRITE | CL_MEM_COPY_HOST_PTR, bytes, z.data(), &status);
  RF_CL_CHECK_CODE(status, "clCreateBuffer(z)");
  // Scratch of the Thomas sweeps, zeroed from the host: every element is written before it is read, but oclgrind
  // follows speculative loads and does not count clEnqueueFillBuffer as initialisation.
  std::vector<float> zeros(z.size(), 0.0f);
  ::cl::Buffer c_buffer(device.context(), CL_MEM_READ_WRITE | CL_MEM_COPY_HOST_PTR, bytes, zeros.data(), &status);
  RF_CL_CHECK_CODE(status, "clCreateBuffer(c)");
  ::cl::Buffer d_buffer(device.context(), CL_MEM_READ_WRITE | CL_MEM_COPY_HOST_PTR, bytes, zeros.data(), &status);
  RF_CL_CHECK_CODE(status, "clCreateBuffer(d)");
  const bool single = entry == KernelEntry::kSingleWorkItem;
  ::cl::Kernel kernel(programs.get(device, "depth/fuse.cl"), single ? "fuse_rows_single" : "fuse_rows_ndrange",
                      &status);
  RF_CL_CHECK_CODE(status, "clCreateKernel(fuse_rows)");
  cl_uint index = set_common_args(kernel, rows, row_begin, row_end, options.iterations);
  RF_CL_CHECK(kernel.setArg(index++, options.sigma_disparity_px));
  RF_CL_CHECK(kernel.setArg(index++, options.sigma_step_mm));
  for (const ::cl::Buffer* buffer : std::initializer_list<const ::cl::Buffer*>{
           &inputs.e_cam, &inputs.e_proj, &inputs.z_tri, &inputs.runs, &z_buffer, &c_buffer, &d_buffer}) {
    RF_CL_CHECK(kernel.setArg(index++, *buffer));
  }
  run_rows(device, kernel, entry, row_end - row_begin);
  RF_CL_CHECK(device.queue().enqueueReadBuffer(z_buffer, CL_TRUE, 0, bytes, z.data()));
  return z;
}

}  // namespace rfrecon::depth
