// Depth along rectified rows: reciprocity integration (the paper's method) and its fusion with triangulated
// positions, as plain C++ references and as OpenCL kernels (kernels/depth/integrate.cl, fuse.cl) on one device.
// Every call covers the row range [row_begin, row_end) and returns its (row_end - row_begin) x width depths (mm,
// rectified camera frame, NaN where masked), so a scheduler can split the rows over devices.
#pragma once

#include <cstdint>
#include <string_view>
#include <vector>

#include "host/cl/device_context.h"
#include "host/cl/kernel_entry.h"
#include "host/cl/program_cache.h"
#include "host/depth/rectified_rows.h"

namespace rfrecon::depth {

using cl::KernelEntry;

struct IntegrationOptions {
  int passes = 3;  // shooting passes per run: the first seeds from triangulation, the others rescale the seed
};

struct FusionOptions {
  int iterations = 3;               // linearised tridiagonal solves per run
  float sigma_disparity_px = 0.1f;  // disparity noise of the correspondences: weight of the positions
  float sigma_step_mm = 0.1f;       // error of one RK4 step of the ODE (intensity noise): weight of the slopes
};

// Rows [row_begin, row_end) of rows.height; throw std::invalid_argument on a bad range or bad options.
std::vector<float> integrate_rows_reference(const RectifiedRows& rows, const IntegrationOptions& options, int row_begin,
                                            int row_end);
// z_start: the starting depth of rows [row_begin, row_end) (typically their integration), same layout as the result.
std::vector<float> fuse_rows_reference(const RectifiedRows& rows, const std::vector<float>& z_start,
                                       const FusionOptions& options, int row_begin, int row_end);

// The rows' inputs as the NDRange entries read them: groups of RF_LANES rows interleaved (kernels/depth/row_lanes.h),
// the last group padded with masked rows. Made once, on every core, for all the tiles of both solvers, which lend
// their part of it instead of each interleaving its own rows.
struct LaneRows {
  int groups = 0;  // of RF_LANES rows
  std::vector<float> e_cam, e_proj, z_tri;
  std::vector<std::uint8_t> runs;
};
LaneRows interleave_rows(const RectifiedRows& rows);

// The kernels of `entry` on one device. The single work-item entries take rows of at most RF_MAX_ROW_WIDTH pixels
// (kernels/common/params.h) and throw ProcessingError on wider ones. `lanes`: interleave_rows(rows), for NDRange
// entries (row_begin a multiple of RF_LANES); without it the call interleaves its rows itself. build_options are
// added to the program's build (the FPGA target macros on PoCL, for the tests that compare the entries).
std::vector<float> integrate_rows_opencl(cl::DeviceContext& device, cl::ProgramCache& programs, KernelEntry entry,
                                         const RectifiedRows& rows, const IntegrationOptions& options, int row_begin,
                                         int row_end, const LaneRows* lanes = nullptr,
                                         std::string_view build_options = {});
std::vector<float> fuse_rows_opencl(cl::DeviceContext& device, cl::ProgramCache& programs, KernelEntry entry,
                                    const RectifiedRows& rows, const std::vector<float>& z_start,
                                    const FusionOptions& options, int row_begin, int row_end,
                                    const LaneRows* lanes = nullptr, std::string_view build_options = {});

}  // namespace rfrecon::depth
