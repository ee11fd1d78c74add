// C simulation of the HLS C++ tops (hw/hls/), what Vitis calls csim: the tops compiled by the host's C++ compiler
// (HLS pragmas ignored) against the C++ references of the row solvers, on the inputs of the OpenCL kernel tests
// (tests/depth/row_solver_inputs.h), in row tiles and with more rows than one interleaved group.
#include <vector>

#include <gtest/gtest.h>

#include "hls/depth_tops.h"
#include "host/depth/row_solvers.h"
#include "tests/depth/row_solver_inputs.h"

namespace rfrecon::depth {
namespace {

using testing::expect_close;

std::size_t tile_offset(const RectifiedRows& rows, int row) { return static_cast<std::size_t>(row) * rows.width; }

// The integration top over rows [row_begin, row_end): its buffers hold the tile's rows only, as the kernels' do.
std::vector<float> integrate_top(const RectifiedRows& rows, int passes, int row_begin, int row_end) {
  std::vector<float> z(tile_offset(rows, row_end) - tile_offset(rows, row_begin));
  const RfRectifiedRig& rig = rows.rig;
  integrate_rows_top(rig.f, rig.cx_cam, rig.cx_proj, rig.cy, rig.b, row_begin, row_end - row_begin, rows.width,
                     rows.proj_width, passes, rows.e_cam.data() + tile_offset(rows, row_begin),
                     rows.e_proj.data() + static_cast<std::size_t>(row_begin) * rows.proj_width,
                     rows.z_tri.data() + tile_offset(rows, row_begin), rows.runs.data() + tile_offset(rows, row_begin),
                     z.data());
  return z;
}

// The fusion top over rows [row_begin, row_end) from z_all (all rows' starting depths).
std::vector<float> fuse_top(const RectifiedRows& rows, const std::vector<float>& z_all, const FusionOptions& options,
                            int row_begin, int row_end) {
  std::vector<float> z(z_all.begin() + static_cast<std::ptrdiff_t>(tile_offset(rows, row_begin)),
                       z_all.begin() + static_cast<std::ptrdiff_t>(tile_offset(rows, row_end)));
  const RfRectifiedRig& rig = rows.rig;
  fuse_rows_top(rig.f, rig.cx_cam, rig.cx_proj, rig.cy, rig.b, row_begin, row_end - row_begin, rows.width,
                rows.proj_width, options.iterations, options.sigma_disparity_px, options.sigma_step_mm,
                rows.e_cam.data() + tile_offset(rows, row_begin),
                rows.e_proj.data() + static_cast<std::size_t>(row_begin) * rows.proj_width,
                rows.z_tri.data() + tile_offset(rows, row_begin), rows.runs.data() + tile_offset(rows, row_begin),
                z.data());
  return z;
}

// The tolerance is the OpenCL kernels' (tests/depth/row_solver_inputs.h): the tops run the same per-row arithmetic
// as the references, only with the rows' pixels interleaved, so they should agree far more closely.
TEST(HlsCsim, IntegrationTopMatchesReferenceOnTiles) {
  const auto rows = testing::kernel_test_rows();
  const auto reference = integrate_rows_reference(rows, IntegrationOptions{3}, 0, rows.height);
  auto z = integrate_top(rows, 3, 0, 2);                     // a tile smaller than one interleaved group
  const auto rest = integrate_top(rows, 3, 2, rows.height);  // one full group and a partial one
  z.insert(z.end(), rest.begin(), rest.end());
  expect_close(z, reference);
}

TEST(HlsCsim, FusionTopMatchesReferenceOnTiles) {
  const auto rows = testing::kernel_test_rows();
  const FusionOptions options;
  const auto start = integrate_rows_reference(rows, IntegrationOptions{3}, 0, rows.height);
  const auto reference = fuse_rows_reference(rows, start, options, 0, rows.height);
  auto z = fuse_top(rows, start, options, 0, 3);
  const auto rest = fuse_top(rows, start, options, 3, rows.height);
  z.insert(z.end(), rest.begin(), rest.end());
  expect_close(z, reference);
}

}  // namespace
}  // namespace rfrecon::depth
