// Plain C++ and OpenCL drivers of the row solvers; the per-row arithmetic is shared with the kernels through
// kernels/depth/row_integration.h and row_fusion.h.
#include "host/depth/row_solvers.h"

#include <algorithm>
#include <cstdint>
#include <limits>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "host/cl/kernel_launch.h"
#include "host/core/errors.h"
#include "kernels/common/params.h"
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

// The single work-item entries hold rows in on-chip buffers of RF_MAX_ROW_WIDTH pixels (kernels/common/params.h).
void check_entry_width(const RectifiedRows& rows, KernelEntry entry) {
  if (entry == KernelEntry::kSingleWorkItem && (rows.width > RF_MAX_ROW_WIDTH || rows.proj_width > RF_MAX_ROW_WIDTH)) {
    throw ProcessingError("rectified rows of " + std::to_string(rows.width) + " camera and " +
                          std::to_string(rows.proj_width) +
                          " projector pixels exceed RF_MAX_ROW_WIDTH = " + std::to_string(RF_MAX_ROW_WIDTH) +
                          " of the single work-item depth kernels: run them as NDRange or rebuild the kernels "
                          "with a larger -DRF_MAX_ROW_WIDTH");
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

constexpr std::size_t kRowsPerWorkGroup = 8;  // NDRange entries: one row per work-item

// The rows a launch covers: on NDRange entries, [row_begin, row_end) padded with masked rows to whole work-groups,
// since the integration's work-items advance in step (RF_ROWS_IN_STEP) and each must reach every barrier; on single
// work-item entries the tile itself.
struct LaunchRows {
  std::size_t group = 1;  // work-group size (NDRange)
  int count = 0;          // rows of the tile
  int padded = 0;         // rows launched

  LaunchRows(const cl::DeviceContext& device, KernelEntry entry, int row_begin, int row_end)
      : count(row_end - row_begin), padded(count) {
    if (entry != KernelEntry::kNdRange) return;
    group = std::min<std::size_t>(kRowsPerWorkGroup, device.info().max_work_group_size);
    const auto groups = (static_cast<std::size_t>(count) + group - 1) / group;
    padded = static_cast<int>(groups * group);
  }
};

// A buffer of the tile's `count` elements of `data` followed by `padded - count` copies of `fill`.
template <typename T>
::cl::Buffer upload_padded(cl::DeviceContext& device, const T* data, std::size_t count, std::size_t padded, T fill) {
  ::cl::Buffer buffer = cl::make_buffer<T>(device.context(), padded, CL_MEM_READ_WRITE);
  cl::write_buffer(device.queue(), buffer, data, count);
  const std::vector<T> padding(padded - count, fill);
  cl::write_buffer(device.queue(), buffer, padding.data(), padding.size(), true, count);
  return buffer;
}

// Device buffers of the inputs for rows [row_begin, row_end), padded with masked rows (zero signal, no depth).
struct RowBuffers {
  ::cl::Buffer e_cam, e_proj, z_tri, runs;

  RowBuffers(cl::DeviceContext& device, const RectifiedRows& rows, int row_begin, const LaunchRows& launch) {
    const int row_end = row_begin + launch.count;
    const std::size_t pixels = offset(rows, row_end) - offset(rows, row_begin);
    const std::size_t padded = static_cast<std::size_t>(launch.padded) * static_cast<std::size_t>(rows.width);
    const std::size_t proj_pixels = proj_offset(rows, row_end) - proj_offset(rows, row_begin);
    const std::size_t proj_padded = static_cast<std::size_t>(launch.padded) * static_cast<std::size_t>(rows.proj_width);
    e_cam = upload_padded(device, rows.e_cam.data() + offset(rows, row_begin), pixels, padded, 0.0f);
    e_proj = upload_padded(device, rows.e_proj.data() + proj_offset(rows, row_begin), proj_pixels, proj_padded, 0.0f);
    z_tri = upload_padded(device, rows.z_tri.data() + offset(rows, row_begin), pixels, padded,
                          std::numeric_limits<float>::quiet_NaN());
    runs = upload_padded(device, rows.runs.data() + offset(rows, row_begin), pixels, padded,
                         static_cast<std::uint8_t>(RF_RUN_MASKED));
  }
};

// Sets the kernel's arguments: those both kernels share (geometry, tile, sizes), then `rest`, and runs it over the
// launch's rows, one work-item per row in fixed work-groups (kNdRange) or one in all. A fixed work-group size: with
// the runtime's choice, which follows the tile's row count, PoCL compiles the kernel again for every new size, on the
// first run of each (docs/performance.md#program-cache).
template <typename... Rest>
void run_rows(cl::DeviceContext& device, ::cl::Kernel& kernel, KernelEntry entry, const RectifiedRows& rows,
              int row_begin, const LaunchRows& launch, int count, const Rest&... rest) {
  const RfRectifiedRig& rig = rows.rig;
  cl::set_args(kernel, rig.f, rig.cx_cam, rig.cx_proj, rig.cy, rig.b, cl_int{row_begin}, cl_int{launch.padded},
               cl_int{rows.width}, cl_int{rows.proj_width}, cl_int{count}, rest...);
  cl::enqueue_kernel(device.queue(), kernel, entry, static_cast<std::size_t>(launch.padded), {launch.group});
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
                                         int row_end, std::string_view build_options) {
  check_range(rows, row_begin, row_end);
  check_options(options);
  check_entry_width(rows, entry);
  const LaunchRows launch(device, entry, row_begin, row_end);
  const RowBuffers inputs(device, rows, row_begin, launch);
  // z also holds each run's seed between passes. It starts defined (NaN) because the compiler may load z and z_tri
  // both before choosing the seed of the first pass (oclgrind reports that load otherwise).
  const std::vector<float> z(static_cast<std::size_t>(launch.padded) * static_cast<std::size_t>(rows.width),
                             std::numeric_limits<float>::quiet_NaN());
  const ::cl::Buffer z_buffer = cl::upload(device.context(), z, CL_MEM_READ_WRITE);
  ::cl::Kernel kernel =
      cl::make_kernel(programs.get(device, "depth/integrate.cl", build_options), "integrate_rows", entry);
  run_rows(device, kernel, entry, rows, row_begin, launch, options.passes, inputs.e_cam, inputs.e_proj, inputs.z_tri,
           inputs.runs, z_buffer);
  return cl::download<float>(device.queue(), z_buffer, offset(rows, row_end) - offset(rows, row_begin));
}

std::vector<float> fuse_rows_opencl(cl::DeviceContext& device, cl::ProgramCache& programs, KernelEntry entry,
                                    const RectifiedRows& rows, const std::vector<float>& z_start,
                                    const FusionOptions& options, int row_begin, int row_end,
                                    std::string_view build_options) {
  std::vector<float> z = checked_fusion_start(rows, z_start, options, row_begin, row_end);
  check_entry_width(rows, entry);
  const LaunchRows launch(device, entry, row_begin, row_end);
  const RowBuffers inputs(device, rows, row_begin, launch);
  const std::size_t padded = static_cast<std::size_t>(launch.padded) * static_cast<std::size_t>(rows.width);
  const ::cl::Buffer z_buffer = upload_padded(device, z.data(), z.size(), padded, 0.0f);
  ::cl::Kernel kernel = cl::make_kernel(programs.get(device, "depth/fuse.cl", build_options), "fuse_rows", entry);
  if (entry == KernelEntry::kSingleWorkItem) {  // its scratch is on chip
    run_rows(device, kernel, entry, rows, row_begin, launch, options.iterations, options.sigma_disparity_px,
             options.sigma_step_mm, inputs.e_cam, inputs.e_proj, inputs.z_tri, inputs.runs, z_buffer);
  } else {
    // Scratch of the Thomas sweeps, zeroed from the host: every element is written before it is read, but oclgrind
    // follows speculative loads and does not count clEnqueueFillBuffer as initialisation.
    const std::vector<float> zeros(padded, 0.0f);
    const ::cl::Buffer c_buffer = cl::upload(device.context(), zeros, CL_MEM_READ_WRITE);
    const ::cl::Buffer d_buffer = cl::upload(device.context(), zeros, CL_MEM_READ_WRITE);
    run_rows(device, kernel, entry, rows, row_begin, launch, options.iterations, options.sigma_disparity_px,
             options.sigma_step_mm, inputs.e_cam, inputs.e_proj, inputs.z_tri, inputs.runs, z_buffer, c_buffer,
             d_buffer);
  }
  cl::read_buffer(device.queue(), z_buffer, z.data(), z.size());
  return z;
}

}  // namespace rfrecon::depth
