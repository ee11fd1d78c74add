// Row solvers of the depth stage: the C++ references against the analytic plane (physics), and the OpenCL kernels
// (both entries, on row tiles) against the references.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <vector>

#include <gtest/gtest.h>

#include "host/cl/device_selection.h"
#include "host/core/errors.h"
#include "host/depth/row_solvers.h"
#include "kernels/common/lanes.h"
#include "kernels/common/params.h"
#include "tests/depth/analytic_rows.h"
#include "tests/depth/row_solver_inputs.h"

namespace rfrecon::depth {
namespace {

using testing::expect_close;
using testing::pseudo_noise;
using testing::tilted_plane;

double rms_error(const std::vector<float>& z, const RectifiedRows& truth, int row_begin) {
  double sum = 0.0;
  for (std::size_t i = 0; i < z.size(); ++i) {
    const double e = z[i] - truth.z_tri[static_cast<std::size_t>(row_begin) * truth.width + i];
    sum += e * e;
  }
  return std::sqrt(sum / static_cast<double>(z.size()));
}

TEST(RowSolversReference, IntegrationFollowsThePlaneFromItsSeed) {
  // Exact images and seeds: what is left is RK4 with linearly interpolated e_cam over 40 px of a plane whose depth
  // changes by ~25 mm along the row. 2 um is 4e-6 of the depth.
  const auto rows = testing::analytic_rows(tilted_plane(), 40, 6);
  const auto z = integrate_rows_reference(rows, IntegrationOptions{1}, 0, rows.height);
  for (std::size_t i = 0; i < z.size(); ++i) EXPECT_NEAR(z[i], rows.z_tri[i], 0.002) << "pixel " << i;
}

TEST(RowSolversReference, ShootingCorrectsABadSeed) {
  // The first pixel of each row (its seed) triangulated 5 mm too far, the others with +-0.5 mm noise: after 3 passes
  // the run's mean residual is zero, so the row sits within the noise's mean plus the seed's share (5 / 40 mm),
  // i.e. within 0.2 mm of the truth, instead of 5 mm off.
  auto rows = testing::analytic_rows(tilted_plane(), 40, 6);
  const auto truth = rows;
  for (std::size_t i = 0; i < rows.z_tri.size(); ++i) rows.z_tri[i] += 0.5f * pseudo_noise(i);
  for (int v = 0; v < rows.height; ++v) rows.z_tri[static_cast<std::size_t>(v) * rows.width] += 5.0f;
  const auto z = integrate_rows_reference(rows, IntegrationOptions{3}, 0, rows.height);
  EXPECT_LT(rms_error(z, truth, 0), 0.2);
}

TEST(RowSolversReference, FusionBeatsNoisyPositions) {
  // +-1 mm noise on the positions (0.71 mm RMS), exact slopes: fusion keeps the slopes and averages the positions,
  // so its error must be well below the positions' (a third of it; it is far smaller in practice).
  auto rows = testing::analytic_rows(tilted_plane(), 40, 6);
  const auto truth = rows;
  for (std::size_t i = 0; i < rows.z_tri.size(); ++i) rows.z_tri[i] += pseudo_noise(i);
  const double noise_rms = rms_error(rows.z_tri, truth, 0);
  FusionOptions options;
  options.sigma_step_mm = 0.01f;
  const auto fused = fuse_rows_reference(rows, rows.z_tri, options, 0, rows.height);
  EXPECT_LT(rms_error(fused, truth, 0), noise_rms / 3.0);
}

TEST(RowSolversReference, MaskedPixelsStayNaNAndCutTheRun) {
  auto rows = testing::analytic_rows(tilted_plane(), 40, 2);
  rows.runs[10] = RF_RUN_MASKED;
  rows.runs[11] = RF_RUN_START;
  rows.z_tri[11] += 5.0f;  // a re-seeded run starts from its own seed, not from the previous run
  const auto z = integrate_rows_reference(rows, IntegrationOptions{1}, 0, 1);
  EXPECT_TRUE(std::isnan(z[10]));
  EXPECT_NEAR(z[11], rows.z_tri[11], 1e-6);
  EXPECT_THROW(integrate_rows_reference(rows, IntegrationOptions{1}, 1, 3), std::invalid_argument);
}

class RowSolversKernel : public ::testing::TestWithParam<KernelEntry> {
 protected:
  void SetUp() override {
    devices_ = cl::open_devices("all");
    rows_ = testing::kernel_test_rows();
  }
  // Both solvers on all of `rows` in one tile, against the references.
  void expect_whole_tile_matches_reference(const RectifiedRows& rows) {
    const IntegrationOptions passes{3};
    const auto integrated = integrate_rows_reference(rows, passes, 0, rows.height);
    expect_close(integrate_rows_opencl(devices_.front(), programs_, GetParam(), rows, passes, 0, rows.height),
                 integrated);
    const FusionOptions options;
    expect_close(fuse_rows_opencl(devices_.front(), programs_, GetParam(), rows, integrated, options, 0, rows.height),
                 fuse_rows_reference(rows, integrated, options, 0, rows.height));
  }

  std::vector<cl::DeviceContext> devices_;
  cl::ProgramCache programs_;
  RectifiedRows rows_;
};

TEST_P(RowSolversKernel, IntegrationMatchesReferenceOnTiles) {
  // Two tiles (rows 0-4 and 5-10) put together equal the reference over all rows: a tile only changes beta's origin.
  const IntegrationOptions options{3};
  const auto reference = integrate_rows_reference(rows_, options, 0, rows_.height);
  auto first = integrate_rows_opencl(devices_.front(), programs_, GetParam(), rows_, options, 0, 5);
  const auto second = integrate_rows_opencl(devices_.front(), programs_, GetParam(), rows_, options, 5, rows_.height);
  first.insert(first.end(), second.begin(), second.end());
  expect_close(first, reference);
}

TEST_P(RowSolversKernel, FusionMatchesReferenceOnTiles) {
  const FusionOptions options;
  const auto start = integrate_rows_reference(rows_, IntegrationOptions{3}, 0, rows_.height);
  const auto reference = fuse_rows_reference(rows_, start, options, 0, rows_.height);
  const auto split = start.begin() + std::ptrdiff_t{3} * rows_.width;  // the first tile's 3 rows
  const std::vector<float> start_first(start.begin(), split), start_second(split, start.end());
  auto first = fuse_rows_opencl(devices_.front(), programs_, GetParam(), rows_, start_first, options, 0, 3);
  const auto second =
      fuse_rows_opencl(devices_.front(), programs_, GetParam(), rows_, start_second, options, 3, rows_.height);
  first.insert(first.end(), second.begin(), second.end());
  expect_close(first, reference);
}

TEST_P(RowSolversKernel, TilesLendingTheInterleavedRowsMatchReference) {
  // Tiles [0, RF_LANES) and [RF_LANES, 11) take their inputs from interleave_rows (the second one's padded lanes
  // past the image's end); the single work-item entry ignores them. A tile that starts inside a group, and the
  // interleaved rows of narrower rows, are refused.
  const LaneRows lanes = interleave_rows(rows_);
  ASSERT_EQ(lanes.groups, 2);
  const IntegrationOptions passes{3};
  const auto integrated = integrate_rows_reference(rows_, passes, 0, rows_.height);
  auto z = integrate_rows_opencl(devices_.front(), programs_, GetParam(), rows_, passes, 0, RF_LANES, &lanes);
  const auto rest =
      integrate_rows_opencl(devices_.front(), programs_, GetParam(), rows_, passes, RF_LANES, rows_.height, &lanes);
  z.insert(z.end(), rest.begin(), rest.end());
  expect_close(z, integrated);

  const FusionOptions options;
  const auto split = integrated.begin() + std::ptrdiff_t{RF_LANES} * rows_.width;
  const std::vector<float> start_first(integrated.begin(), split), start_second(split, integrated.end());
  auto fused =
      fuse_rows_opencl(devices_.front(), programs_, GetParam(), rows_, start_first, options, 0, RF_LANES, &lanes);
  const auto fused_rest = fuse_rows_opencl(devices_.front(), programs_, GetParam(), rows_, start_second, options,
                                           RF_LANES, rows_.height, &lanes);
  fused.insert(fused.end(), fused_rest.begin(), fused_rest.end());
  expect_close(fused, fuse_rows_reference(rows_, integrated, options, 0, rows_.height));

  if (GetParam() == KernelEntry::kNdRange) {
    EXPECT_THROW(integrate_rows_opencl(devices_.front(), programs_, GetParam(), rows_, passes, 3, rows_.height, &lanes),
                 std::invalid_argument);
    const LaneRows narrower = interleave_rows(testing::analytic_rows(testing::tilted_plane(), 16, rows_.height));
    EXPECT_THROW(integrate_rows_opencl(devices_.front(), programs_, GetParam(), rows_, passes, 0, RF_LANES, &narrower),
                 std::invalid_argument);
  }
}

TEST_P(RowSolversKernel, RowsOfDifferentRunsSideBySideMatchReference) {
  // 19 rows in one tile: two whole groups of RF_LANES rows and a padded one on the NDRange entry, whose lanes meet
  // masked pixels, run starts and ends at different columns: a row masked at its start, one cut in three runs, one
  // masked throughout, one whose run starts at its last pixel.
  static_assert(19 % RF_LANES != 0 && 19 > 2 * RF_LANES, "the test needs two whole groups of lanes and a partial one");
  auto rows = testing::kernel_test_rows(19);
  const auto code = [&](int row, int u) -> std::uint8_t& {
    return rows.runs[static_cast<std::size_t>(row) * static_cast<std::size_t>(rows.width) + u];
  };
  for (int u = 0; u < 3; ++u) code(9, u) = RF_RUN_MASKED;
  code(9, 3) = RF_RUN_START;
  code(12, 8) = RF_RUN_START;
  code(12, 15) = RF_RUN_MASKED;
  code(12, 16) = RF_RUN_START;
  for (int u = 0; u < rows.width; ++u) code(17, u) = RF_RUN_MASKED;
  code(18, rows.width - 1) = RF_RUN_START;
  expect_whole_tile_matches_reference(rows);
}

TEST_P(RowSolversKernel, ColumnsMaskedInEveryRowMatchReference) {
  // Columns 5 to 7 masked in all 19 rows, every run restarting at column 8: on the NDRange entry each group of lanes
  // meets pixels where every lane is masked, and at column 4 a pixel where no lane links to the next, whose work the
  // lanes skip (RF_ANY).
  auto rows = testing::kernel_test_rows(19);
  for (int v = 0; v < rows.height; ++v) {
    std::uint8_t* row = rows.runs.data() + static_cast<std::size_t>(v) * static_cast<std::size_t>(rows.width);
    for (int u = 5; u < 8; ++u) row[u] = RF_RUN_MASKED;
    row[8] = RF_RUN_START;
  }
  expect_whole_tile_matches_reference(rows);
}

TEST(RowSolversKernelWidth, SingleEntriesRefuseRowsWiderThanTheirBuffers) {
  // One row of RF_MAX_ROW_WIDTH + 1 pixels: refused before any upload by the single work-item entries, whose on-chip
  // buffers hold RF_MAX_ROW_WIDTH pixels (the NDRange entries have no such limit).
  auto devices = cl::open_devices("all");
  cl::ProgramCache programs;
  const auto rows = testing::analytic_rows(tilted_plane(), RF_MAX_ROW_WIDTH + 1, 1);
  const IntegrationOptions options{1};
  EXPECT_THROW(integrate_rows_opencl(devices.front(), programs, KernelEntry::kSingleWorkItem, rows, options, 0, 1),
               ProcessingError);
  EXPECT_THROW(fuse_rows_opencl(devices.front(), programs, KernelEntry::kSingleWorkItem, rows, rows.z_tri,
                                FusionOptions{}, 0, 1),
               ProcessingError);
}

INSTANTIATE_TEST_SUITE_P(Entries, RowSolversKernel,
                         ::testing::Values(KernelEntry::kNdRange, KernelEntry::kSingleWorkItem),
                         [](const auto& info) { return info.param == KernelEntry::kNdRange ? "NdRange" : "Single"; });

}  // namespace
}  // namespace rfrecon::depth
