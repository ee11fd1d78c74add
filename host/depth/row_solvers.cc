// Plain C++ and OpenCL drivers of the row solvers; the per-row arithmetic is shared with the kernels through
// kernels/depth/row_integration.h and row_fusion.h.
#include "host/depth/row_solvers.h"

#include <algorithm>
#include <cstdint>
#include <limits>
#include <stdexcept>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "host/cl/kernel_launch.h"
#include "host/core/errors.h"
#include "host/core/parallel_rows.h"
#include "kernels/common/lanes.h"
#include "kernels/common/params.h"
#include "kernels/depth/row_buffers.h"
#include "kernels/depth/row_fusion.h"
#include "kernels/depth/row_integration.h"

namespace rfrecon::depth {

namespace {

// The single work-item entries' interleaved rows are private arrays (on-chip memory on a board): CPU runtimes need
// worker stacks that hold them, declared before any device is opened.
constexpr std::size_t kPrivateRowBytes =
    RF_INTEGRATE_PRIVATE_BYTES > RF_FUSE_PRIVATE_BYTES ? RF_INTEGRATE_PRIVATE_BYTES : RF_FUSE_PRIVATE_BYTES;
[[maybe_unused]] const bool kPrivateRowsReserved = cl::reserve_private_bytes(kPrivateRowBytes);

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

// The fusion's arguments checked.
void check_fusion_start(const RectifiedRows& rows, const std::vector<float>& z_start, const FusionOptions& options,
                        int row_begin, int row_end) {
  check_range(rows, row_begin, row_end);
  check_options(options);
  if (z_start.size() != offset(rows, row_end) - offset(rows, row_begin)) {
    throw std::invalid_argument("fusion: the starting depth does not cover the row range");
  }
}

std::size_t proj_offset(const RectifiedRows& rows, int row) {
  return static_cast<std::size_t>(row) * static_cast<std::size_t>(rows.proj_width);
}

// The rows a launch covers. NDRange entries: a work-item per RF_LANES rows, interleaved (kernels/depth/row_lanes.h),
// [row_begin, row_end) padded with masked rows to whole groups of lanes. Single work-item entries: the tile itself.
struct LaunchRows {
  bool lanes = false;
  int count = 0;   // rows of the tile
  int padded = 0;  // rows launched

  LaunchRows(KernelEntry entry, int row_begin, int row_end)
      : lanes(entry == KernelEntry::kNdRange), count(row_end - row_begin), padded(count) {
    if (lanes) padded = (count + RF_LANES - 1) / RF_LANES * RF_LANES;
  }
  std::size_t work_items() const { return lanes ? static_cast<std::size_t>(padded / RF_LANES) : 1; }

  // The tile's `count` rows of `width` elements at `data`, in the launch's layout, the padding rows `fill`; groups of
  // lanes on every core.
  template <typename T>
  std::vector<T> layout(const T* data, int width, T fill) const {
    const auto w = static_cast<std::size_t>(width);
    std::vector<T> out(static_cast<std::size_t>(padded) * w, fill);
    if (!lanes) {
      std::copy(data, data + static_cast<std::size_t>(count) * w, out.begin());
      return out;
    }
    // Written in order, lane by lane within each pixel of a group.
    for_each_row(padded / RF_LANES, [&](int g) {
      const auto group = static_cast<std::size_t>(g);
      const std::size_t lanes_in_tile = std::min<std::size_t>(RF_LANES, count - group * RF_LANES);
      const T* group_rows = data + group * RF_LANES * w;
      T* group_out = out.data() + group * w * RF_LANES;
      for (std::size_t u = 0; u < w; ++u) {
        for (std::size_t lane = 0; lane < lanes_in_tile; ++lane)
          group_out[u * RF_LANES + lane] = group_rows[lane * w + u];
      }
    });
    return out;
  }

  // The tile's rows back from the launch's layout, on every core.
  std::vector<float> rows_of(std::vector<float> launched, int width) const {
    if (!lanes) return launched;  // the tile itself
    const auto w = static_cast<std::size_t>(width);
    std::vector<float> out(static_cast<std::size_t>(count) * w);
    for_each_row(count, [&](int r) {
      const auto row = static_cast<std::size_t>(r);
      const std::size_t group = row / RF_LANES, lane = row % RF_LANES;
      for (std::size_t u = 0; u < w; ++u) out[row * w + u] = launched[(group * w + u) * RF_LANES + lane];
    });
    return out;
  }
};

// The inputs for rows [row_begin, row_end) in the launch's layout, padded with masked rows (zero signal, no depth),
// and buffers over them (cl::borrow: no copy where kernels run on host memory): the launch's part of `lanes` where
// given (NDRange), else its own copy. Keep it and `lanes` alive until the kernel ran.
class RowBuffers {
 public:
  ::cl::Buffer e_cam, e_proj, z_tri, runs;

  RowBuffers(cl::DeviceContext& device, const RectifiedRows& rows, int row_begin, const LaunchRows& launch,
             const LaneRows* lanes) {
    const ::cl::Context& context = device.context();
    if (lanes != nullptr && launch.lanes) {
      const int padded_height = (rows.height + RF_LANES - 1) / RF_LANES * RF_LANES;
      const std::size_t camera = offset(rows, padded_height), projector = proj_offset(rows, padded_height);
      if (lanes->groups * RF_LANES != padded_height || lanes->e_cam.size() != camera ||
          lanes->e_proj.size() != projector || lanes->z_tri.size() != camera || lanes->runs.size() != camera) {
        throw std::invalid_argument("interleaved rows: not those of these rectified rows (interleave_rows(rows))");
      }
      if (row_begin % RF_LANES != 0) {
        throw std::invalid_argument("interleaved rows: the tile starts at row " + std::to_string(row_begin) +
                                    ", not at a multiple of RF_LANES = " + std::to_string(RF_LANES));
      }
      const std::size_t first = offset(rows, row_begin), count = offset(rows, launch.padded);
      const auto part = [&](const auto& whole) { return cl::borrow(context, whole.data() + first, count); };
      e_cam = part(lanes->e_cam);
      e_proj =
          cl::borrow(context, lanes->e_proj.data() + proj_offset(rows, row_begin), proj_offset(rows, launch.padded));
      z_tri = part(lanes->z_tri);
      runs = part(lanes->runs);
      return;
    }
    e_cam_rows_ = launch.layout(rows.e_cam.data() + offset(rows, row_begin), rows.width, 0.0f);
    e_proj_rows_ = launch.layout(rows.e_proj.data() + proj_offset(rows, row_begin), rows.proj_width, 0.0f);
    z_tri_rows_ =
        launch.layout(rows.z_tri.data() + offset(rows, row_begin), rows.width, std::numeric_limits<float>::quiet_NaN());
    run_rows_ =
        launch.layout(rows.runs.data() + offset(rows, row_begin), rows.width, static_cast<std::uint8_t>(RF_RUN_MASKED));
    const auto borrow = [&](const auto& data) { return cl::borrow(context, data.data(), data.size()); };
    e_cam = borrow(e_cam_rows_);
    e_proj = borrow(e_proj_rows_);
    z_tri = borrow(z_tri_rows_);
    runs = borrow(run_rows_);
  }

 private:
  std::vector<float> e_cam_rows_, e_proj_rows_, z_tri_rows_;
  std::vector<std::uint8_t> run_rows_;
};

// Sets the kernel's arguments: those both kernels share (geometry, tile, sizes), then `rest`, and runs it over the
// launch's rows: on NDRange entries in work-groups of one work-item (a fixed size: with the runtime's choice, which
// follows the tile's row count, PoCL compiles the kernel again for every new size, docs/performance.md#program-cache).
template <typename... Rest>
void run_rows(cl::DeviceContext& device, ::cl::Kernel& kernel, KernelEntry entry, const RectifiedRows& rows,
              int row_begin, const LaunchRows& launch, int count, const Rest&... rest) {
  const RfRectifiedRig& rig = rows.rig;
  cl::set_args(kernel, rig.f, rig.cx_cam, rig.cx_proj, rig.cy, rig.b, cl_int{row_begin}, cl_int{launch.padded},
               cl_int{rows.width}, cl_int{rows.proj_width}, cl_int{count}, rest...);
  cl::enqueue_kernel(device.queue(), kernel, entry, launch.work_items(), {1});
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
  check_fusion_start(rows, z_start, options, row_begin, row_end);
  std::vector<float> z = z_start;
  std::vector<float> c(static_cast<std::size_t>(rows.width)), d(c.size());
  for (int row = row_begin; row < row_end; ++row) {
    rf_fuse_row(rows.rig, rows.beta(row), rows.width, rows.proj_width, options.iterations,
                rf_fusion_weights(rows.rig, options.sigma_disparity_px, options.sigma_step_mm),
                rows.e_cam.data() + offset(rows, row), rows.e_proj.data() + proj_offset(rows, row),
                rows.z_tri.data() + offset(rows, row), rows.runs.data() + offset(rows, row),
                z.data() + offset(rows, row - row_begin), c.data(), d.data());
  }
  return z;
}

LaneRows interleave_rows(const RectifiedRows& rows) {
  const LaunchRows whole(KernelEntry::kNdRange, 0, rows.height);
  LaneRows lanes;
  lanes.groups = whole.padded / RF_LANES;
  lanes.e_cam = whole.layout(rows.e_cam.data(), rows.width, 0.0f);
  lanes.e_proj = whole.layout(rows.e_proj.data(), rows.proj_width, 0.0f);
  lanes.z_tri = whole.layout(rows.z_tri.data(), rows.width, std::numeric_limits<float>::quiet_NaN());
  lanes.runs = whole.layout(rows.runs.data(), rows.width, static_cast<std::uint8_t>(RF_RUN_MASKED));
  return lanes;
}

std::vector<float> integrate_rows_opencl(cl::DeviceContext& device, cl::ProgramCache& programs, KernelEntry entry,
                                         const RectifiedRows& rows, const IntegrationOptions& options, int row_begin,
                                         int row_end, const LaneRows* lanes, std::string_view build_options) {
  check_range(rows, row_begin, row_end);
  check_options(options);
  check_entry_width(rows, entry);
  const LaunchRows launch(entry, row_begin, row_end);
  const RowBuffers inputs(device, rows, row_begin, launch, lanes);
  // z also holds each run's seed between passes. It starts defined (NaN) because a run's first pixel reads its seed
  // of the pass before, and discards it in the first pass (oclgrind reports the load otherwise).
  std::vector<float> z(static_cast<std::size_t>(launch.padded) * static_cast<std::size_t>(rows.width),
                       std::numeric_limits<float>::quiet_NaN());
  {  // the buffer over z and the kernel go before z does
    const ::cl::Buffer z_buffer = cl::share(device.context(), z);
    ::cl::Kernel kernel =
        cl::make_kernel(programs.get(device, "depth/integrate.cl", build_options), "integrate_rows", entry);
    run_rows(device, kernel, entry, rows, row_begin, launch, options.passes, inputs.e_cam, inputs.e_proj, inputs.z_tri,
             inputs.runs, z_buffer);
    cl::sync_to_host(device.queue(), z_buffer);
  }
  return launch.rows_of(std::move(z), rows.width);
}

std::vector<float> fuse_rows_opencl(cl::DeviceContext& device, cl::ProgramCache& programs, KernelEntry entry,
                                    const RectifiedRows& rows, const std::vector<float>& z_start,
                                    const FusionOptions& options, int row_begin, int row_end, const LaneRows* lanes,
                                    std::string_view build_options) {
  check_fusion_start(rows, z_start, options, row_begin, row_end);
  check_entry_width(rows, entry);
  const LaunchRows launch(entry, row_begin, row_end);
  const RowBuffers inputs(device, rows, row_begin, launch, lanes);
  std::vector<float> z_launched = launch.layout(z_start.data(), rows.width, 0.0f);
  // The NDRange entry's scratch of the Thomas sweeps (the single work-item entry's is on chip), zeroed from the host:
  // every element is written before it is read, but oclgrind follows speculative loads and does not count
  // clEnqueueFillBuffer as initialisation.
  const bool scratch = entry == KernelEntry::kNdRange;
  std::vector<float> c(scratch ? z_launched.size() : 0, 0.0f), d(c.size(), 0.0f);
  {  // the buffers over these vectors and the kernel go before the vectors do
    const ::cl::Buffer z_buffer = cl::share(device.context(), z_launched);
    ::cl::Kernel kernel = cl::make_kernel(programs.get(device, "depth/fuse.cl", build_options), "fuse_rows", entry);
    if (scratch) {
      const ::cl::Buffer c_buffer = cl::share(device.context(), c), d_buffer = cl::share(device.context(), d);
      run_rows(device, kernel, entry, rows, row_begin, launch, options.iterations, options.sigma_disparity_px,
               options.sigma_step_mm, inputs.e_cam, inputs.e_proj, inputs.z_tri, inputs.runs, z_buffer, c_buffer,
               d_buffer);
    } else {
      run_rows(device, kernel, entry, rows, row_begin, launch, options.iterations, options.sigma_disparity_px,
               options.sigma_step_mm, inputs.e_cam, inputs.e_proj, inputs.z_tri, inputs.runs, z_buffer);
    }
    cl::sync_to_host(device.queue(), z_buffer);
  }
  return launch.rows_of(std::move(z_launched), rows.width);
}

}  // namespace rfrecon::depth
