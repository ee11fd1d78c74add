// The single work-item kernels built with each FPGA target macro (RF_TARGET_INTEL_FPGA, RF_TARGET_XILINX_FPGA: the
// vendor attributes and pragmas of kernels/common/target.h, which PoCL's clang ignores, and the compression's
// divisions by the compile-time dot spacings) and run on the first OpenCL device (PoCL in CI): the depth kernels
// equal their NDRange twins built without a macro on the row tiles of the kernel tests, also with an interleave that
// does not divide the tiles' rows (3); the transport kernels, Gray code and phase shifting, equal the C++ reference on
// the tiny captures. What this
// shows: the macros leave the kernels' arithmetic unchanged; not what a vendor compiler makes of them.
#include <algorithm>
#include <sstream>
#include <string>
#include <string_view>
#include <tuple>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "host/cl/device_selection.h"
#include "host/cl/kernel_sources.h"
#include "host/depth/row_solvers.h"
#include "host/transport/phase_accumulators.h"
#include "host/transport/spmv.h"
#include "tests/depth/row_solver_inputs.h"
#include "tests/transport/same_phase_transport.h"
#include "tests/transport/same_transport.h"
#include "tests/transport/test_capture_feed.h"

namespace rfrecon::depth {
namespace {

using testing::expect_close;

struct Build {
  const char* name;     // the test's name
  const char* options;  // the single work-item program's build options
};

class FpgaMacrosOnPocl : public ::testing::TestWithParam<Build> {
 protected:
  void SetUp() override {
    devices_ = cl::open_devices("all");
    rows_ = testing::kernel_test_rows();
  }
  std::string options() const { return GetParam().options; }
  std::vector<cl::DeviceContext> devices_;
  cl::ProgramCache programs_;
  RectifiedRows rows_;
};

TEST_P(FpgaMacrosOnPocl, IntegrationSingleEqualsNdRange) {
  const IntegrationOptions options{3};
  cl::DeviceContext& device = devices_.front();
  for (const auto& [begin, end] : {std::pair{0, 5}, std::pair{5, rows_.height}}) {
    expect_close(integrate_rows_opencl(device, programs_, KernelEntry::kSingleWorkItem, rows_, options, begin, end,
                                       nullptr, this->options()),
                 integrate_rows_opencl(device, programs_, KernelEntry::kNdRange, rows_, options, begin, end));
  }
}

TEST_P(FpgaMacrosOnPocl, FusionSingleEqualsNdRange) {
  const FusionOptions options;
  cl::DeviceContext& device = devices_.front();
  const auto start = integrate_rows_reference(rows_, IntegrationOptions{3}, 0, rows_.height);
  const auto split = start.begin() + 3 * rows_.width;
  const std::vector<float> start_first(start.begin(), split), start_second(split, start.end());
  for (const auto& [begin, end, z] : {std::tuple{0, 3, start_first}, std::tuple{3, rows_.height, start_second}}) {
    expect_close(fuse_rows_opencl(device, programs_, KernelEntry::kSingleWorkItem, rows_, z, options, begin, end,
                                  nullptr, this->options()),
                 fuse_rows_opencl(device, programs_, KernelEntry::kNdRange, rows_, z, options, begin, end));
  }
}

// Decode, compression over several batches (s = 5: 25 frames) and the sparse products, K = 4 (another K than the
// parameters header's, as `rfrecon transport -k 4` builds it).
TEST_P(FpgaMacrosOnPocl, TransportSingleEqualsReference) {
  const auto capture = transport::testing::tiny_capture(5);
  const auto linear = transport::testing::linearize(capture.frames);
  const auto setup = transport::testing::setup_for(linear, capture.scene.projector_size, 5, 4);
  auto reference = transport::make_reference_accumulator(setup);
  const auto expected = transport::testing::feed_all(*reference, capture.sequence, linear);
  auto single =
      transport::make_device_accumulator(setup, devices_.front(), programs_, KernelEntry::kSingleWorkItem, options());
  transport::testing::expect_same_transport(transport::testing::feed_all(*single, capture.sequence, linear), expected);

  const std::vector<float> light_p(expected.projector_pixels(), 0.5f);
  const std::vector<float> light_c(expected.camera_pixels(), 0.25f);
  EXPECT_EQ(
      transport::primal_opencl(devices_.front(), programs_, KernelEntry::kSingleWorkItem, expected, light_p, options()),
      transport::primal_reference(expected, light_p));
  EXPECT_EQ(transport::dual_opencl(devices_.front(), programs_, KernelEntry::kSingleWorkItem,
                                   transport::transpose(expected), light_c, options()),
            transport::dual_reference(expected, light_c));
}

// Gray pairs over one full batch of RF_GRAY_PAIR_BATCH and a partial one.
TEST_P(FpgaMacrosOnPocl, GrayPairsOverAFullAndAPartialBatchEqualReference) {
  const auto capture = transport::testing::tiny_gray_capture_over_batches();
  if (!capture) GTEST_SKIP() << "no tiny partial batch of Gray pairs";
  const auto linear = transport::testing::linearize(capture->frames);
  const auto setup = transport::testing::setup_for(linear, capture->scene.projector_size, 0, 2);
  auto reference = transport::make_reference_accumulator(setup);
  const auto expected = transport::testing::feed_all(*reference, capture->sequence, linear);
  auto single =
      transport::make_device_accumulator(setup, devices_.front(), programs_, KernelEntry::kSingleWorkItem, options());
  transport::testing::expect_same_transport(transport::testing::feed_all(*single, capture->sequence, linear), expected);
}

// The phase steps over a full and a partial batch of RF_FRAME_BATCH, the order pairs and the finalizing; the folds of
// longer periods (ratio 2); a dot grid of 25 frames after the phases; another tool's conventions; heterodyne beats.
TEST_P(FpgaMacrosOnPocl, PhaseSingleEqualsReference) {
  for (const transport::testing::PhaseParameters phase :
       {transport::testing::PhaseParameters{RF_FRAME_BATCH + 2, 6}, transport::testing::PhaseParameters{4, 4, 2},
        transport::testing::PhaseParameters{4, 4, 0, 5}, transport::testing::PhaseParameters{3, 4, 0, 0, 270, 1, 2, 0},
        transport::testing::PhaseParameters{5, 4, 0, 0, 0, 0, 1, 1, 0, 4, 2, 24, 16}}) {
    SCOPED_TRACE("ratio " + std::to_string(phase.ratio) + " dots " + std::to_string(phase.dot_spacing));
    const auto capture = transport::testing::tiny_phase_capture(phase);
    const auto linear = transport::testing::linearize(capture.frames);
    const auto setup = transport::testing::phase_setup_for(linear, phase, 2);
    const auto expected = transport::testing::feed_plan(*transport::make_phase_reference_accumulator(setup), "phase",
                                                        capture.sequence, linear, linear);
    auto single = transport::make_phase_device_accumulator(setup, devices_.front(), programs_,
                                                           KernelEntry::kSingleWorkItem, options());
    transport::testing::expect_same_phase_transport(
        transport::testing::feed_plan(*single, "phase", capture.sequence, linear, linear), expected);
  }
}

// A board binary holds the single work-item entries alone: every kernel file built with the target's macro declares
// its `_single` entries and no NDRange entry (RF_NDRANGE_ENTRIES, kernels/common/target.h); built without it, both.
TEST_P(FpgaMacrosOnPocl, BoardProgramsHoldOnlySingleWorkItemEntries) {
  const auto names_in = [&](std::string_view path, const std::string& options) {
    const ::cl::Program program = programs_.get(devices_.front(), path, options);
    std::vector<std::string> names;
    std::stringstream listed(program.getInfo<CL_PROGRAM_KERNEL_NAMES>());
    for (std::string name; std::getline(listed, name, ';');) names.push_back(name);
    std::sort(names.begin(), names.end());
    return names;
  };
  for (const auto& file : cl::embedded_kernel_files()) {
    if (file.path.size() < 3 || file.path.substr(file.path.size() - 3) != ".cl") continue;
    SCOPED_TRACE(std::string(file.path));
    const std::vector<std::string> board = names_in(file.path, options());
    const std::vector<std::string> everywhere = names_in(file.path, "");
    ASSERT_FALSE(board.empty());
    std::vector<std::string> twins;
    for (const auto& name : board) {
      ASSERT_TRUE(name.size() > 7 && name.substr(name.size() - 7) == "_single") << name;
      twins.push_back(name.substr(0, name.size() - 7) + "_ndrange");
      twins.push_back(name);
    }
    std::sort(twins.begin(), twins.end());
    EXPECT_EQ(everywhere, twins);
  }
}

INSTANTIATE_TEST_SUITE_P(
    Targets, FpgaMacrosOnPocl,
    ::testing::Values(Build{"Intel", "-DRF_TARGET_INTEL_FPGA"}, Build{"Xilinx", "-DRF_TARGET_XILINX_FPGA"},
                      Build{"IntelInterleave3",
                            "-DRF_TARGET_INTEL_FPGA -DRF_INTEGRATE_INTERLEAVE=3 -DRF_FUSE_INTERLEAVE=3"}),
    [](const auto& info) { return std::string(info.param.name); });

}  // namespace
}  // namespace rfrecon::depth
