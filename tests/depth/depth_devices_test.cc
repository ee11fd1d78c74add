// The depth stage over several devices: rows cut into tiles by the scheduler give the same depth, bit for bit, as one
// device (every row is solved alone by the same kernel), and with one device on the single work-item entries and the
// other on NDRange (a CPU + FPGA run) the same depth within the row-solver kernel tests' tolerance. Needs two
// devices: run by depth_two_pocl_devices with POCL_DEVICES="pthread pthread"; skipped where only one device exists.
#include <algorithm>
#include <cmath>
#include <cstring>
#include <functional>
#include <memory>

#include <gtest/gtest.h>

#include "host/cl/device_selection.h"
#include "host/depth/reconstruct_depth.h"
#include "host/transport/compute_transport.h"
#include "sim/frames.h"
#include "sim/render.h"
#include "sim/truth_io.h"
#include "tests/common/devices.h"
#include "tests/sim/test_scenes.h"
#include "tests/transport/synthetic_capture.h"

namespace rfrecon::depth {
namespace {

bool same_bits(const cv::Mat& a, const cv::Mat& b) {
  return a.size() == b.size() && a.type() == b.type() &&
         std::memcmp(a.data, b.data, a.total() * a.elemSize()) == 0;  // NaN where NaN, every float equal
}

// A tilted plane on the small 80x60 test rig, captured with the dot grid and compressed (once for the suite).
struct Scan {
  transport::CompressedTransport transport;
  calib::StereoRig rig;
};

class DepthDevicesTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    sim::Scene scene = sim::testing::make_scene(
        sim::testing::small_rig({sim::testing::tilted_plane({{"brdf", "lambert"}, {"diffuse", 0.6}})}));
    scene.capture.dot_spacing = 5;
    const auto rendered = sim::render_transport(scene);
    transport::testing::TempDir dir("depth_devices");
    sim::write_capture(rendered.T, scene.capture, scene.camera.size, scene.projector.size, 1, 2, dir.path());
    scan_ = std::make_unique<Scan>(Scan{
        transport::compute_transport(dir.path(), capture::read_manifest(dir.path()), {},
                                     [](const auto& setup) { return transport::make_reference_accumulator(setup); })
            .transport,
        sim::true_rig(scene)});
  }
  static void TearDownTestSuite() { scan_.reset(); }

  void SetUp() override {
    if (devices_.size() < 2) GTEST_SKIP() << rfrecon::testing::kNeedTwoDevices;
    devices_.erase(devices_.begin() + 2, devices_.end());
  }

  DepthRun reconstruct(std::vector<cl::DeviceContext>& devices, const DepthOptions& options) {
    return reconstruct_depth(scan_->transport, scan_->rig, "true rig", options, devices, programs_);
  }
  DepthRun on_one_device() {
    std::vector<cl::DeviceContext> one{devices_.front()};
    auto run = reconstruct(one, DepthOptions{});
    EXPECT_GT(run.summary.at("reconstructed_pixels").get<int>(), 0);
    return run;
  }

  // Which device takes which rows is a race (a stage of 60 rows lasts milliseconds, and one device may drain the
  // queue before the other has started), so the two-device run is repeated until both devices delivered items in
  // every stage named in `stages`; `check` runs on every run, and one run must have split the work (else this proves
  // nothing).
  void until_both_delivered(const DepthOptions& options, const std::vector<std::string>& stages,
                            const std::function<void(const DepthRun&)>& check) {
    const auto every_device_delivered = [&](const nlohmann::json& summary) {
      for (const auto& report : summary.at("scheduler")) {
        if (std::find(stages.begin(), stages.end(), report.at("stage").get<std::string>()) == stages.end()) continue;
        for (const auto& device : report.at("devices")) {
          if (device.at("items").get<int>() == 0) return false;
        }
      }
      return true;
    };
    constexpr int kAttempts = 200;  // under load one device may drain every stage in most runs
    bool split = false;
    for (int attempt = 0; attempt < kAttempts && !split; ++attempt) {
      SCOPED_TRACE("attempt " + std::to_string(attempt));
      const auto both = reconstruct(devices_, options);
      check(both);
      if (HasFailure()) return;
      split = every_device_delivered(both.summary);
    }
    EXPECT_TRUE(split) << "no run of " << kAttempts << " gave work to both devices";
  }

  static std::unique_ptr<Scan> scan_;
  std::vector<cl::DeviceContext> devices_ = cl::open_devices("all");
  cl::ProgramCache programs_;
};

std::unique_ptr<Scan> DepthDevicesTest::scan_;

TEST_F(DepthDevicesTest, FusedDepthOnTwoDevicesEqualsOneDevice) {
  const auto single = on_one_device();
  until_both_delivered(DepthOptions{}, {"integrate", "fuse"}, [&](const DepthRun& both) {
    ASSERT_TRUE(same_bits(single.maps.depth_mm, both.maps.depth_mm));
    ASSERT_TRUE(same_bits(single.maps.normals, both.maps.normals));
  });
}

// The tolerance of row_solvers_kernel_test, where each entry's integration and fusion are held to the C++
// reference: 1e-5 relative (6 um at 600 mm), for OpenCL's sqrt and division differing from the host's by an ulp or
// two after a row of RK4 steps. The products feeding the rectification are held to 1e-5 relative there too.
constexpr float kDepthRelativeTolerance = 1e-5f;

TEST_F(DepthDevicesTest, FusedDepthWithASingleWorkItemDeviceAndAnNdRangeDeviceIsTheOneDeviceDepth) {
  const auto expected = on_one_device();
  DepthOptions mixed;
  mixed.entries = cl::EntryChoice({cl::KernelEntry::kSingleWorkItem, cl::KernelEntry::kNdRange});
  until_both_delivered(mixed, {"primal", "dual", "integrate", "fuse"}, [&](const DepthRun& both) {
    for (const auto& report : both.summary.at("scheduler")) {
      ASSERT_EQ(report.at("devices").size(), 2u);
      EXPECT_EQ(report.at("devices")[0].at("entry"), "single") << report.at("stage");
      EXPECT_EQ(report.at("devices")[1].at("entry"), "ndrange") << report.at("stage");
    }
    const cv::Mat& want = expected.maps.depth_mm;
    const cv::Mat& got = both.maps.depth_mm;
    ASSERT_EQ(got.size(), want.size());
    int compared = 0;
    for (int y = 0; y < want.rows; ++y) {
      for (int x = 0; x < want.cols; ++x) {
        const float w = want.at<float>(y, x), g = got.at<float>(y, x);
        if (std::isnan(w)) {
          ASSERT_TRUE(std::isnan(g)) << "pixel " << x << ", " << y;
        } else {
          ASSERT_NEAR(g, w, kDepthRelativeTolerance * std::abs(w)) << "pixel " << x << ", " << y;
          ++compared;
        }
      }
    }
    EXPECT_EQ(compared, expected.summary.at("reconstructed_pixels").get<int>());
  });
}

}  // namespace
}  // namespace rfrecon::depth
