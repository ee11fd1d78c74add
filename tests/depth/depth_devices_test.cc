// The depth stage over several devices: rows cut into tiles by the scheduler give the same depth, bit for bit, as one
// device (every row is solved alone by the same kernel). Needs two devices: run by depth_two_pocl_devices with
// POCL_DEVICES="pthread pthread"; skipped where only one device exists.
#include <cmath>
#include <cstring>

#include <gtest/gtest.h>

#include "host/cl/device_selection.h"
#include "host/depth/reconstruct_depth.h"
#include "host/transport/compute_transport.h"
#include "sim/frames.h"
#include "sim/render.h"
#include "sim/truth_io.h"
#include "tests/sim/test_scenes.h"
#include "tests/transport/synthetic_capture.h"

namespace rfrecon::depth {
namespace {

bool same_bits(const cv::Mat& a, const cv::Mat& b) {
  return a.size() == b.size() && a.type() == b.type() &&
         std::memcmp(a.data, b.data, a.total() * a.elemSize()) == 0;  // NaN where NaN, every float equal
}

TEST(DepthDevicesTest, FusedDepthOnTwoDevicesEqualsOneDevice) {
  auto devices = cl::open_devices("all");
  if (devices.size() < 2) GTEST_SKIP() << "needs two OpenCL devices (POCL_DEVICES=\"pthread pthread\")";
  // A tilted plane on the small 80x60 test rig, captured with the dot grid and compressed.
  sim::Scene scene = sim::testing::make_scene(
      sim::testing::small_rig({sim::testing::tilted_plane({{"brdf", "lambert"}, {"diffuse", 0.6}})}));
  scene.capture.dot_spacing = 5;
  const auto rendered = sim::render_transport(scene);
  transport::testing::TempDir dir("depth_devices");
  sim::write_capture(rendered.T, scene.capture, scene.camera.size, scene.projector.size, 1, 2, dir.path());
  const auto transport =
      transport::compute_transport(dir.path(), capture::read_manifest(dir.path()), {}, [](const auto& setup) {
        return transport::make_reference_accumulator(setup);
      }).transport;
  const calib::StereoRig rig = sim::true_rig(scene);
  cl::ProgramCache programs;
  std::vector<cl::DeviceContext> one{devices.front()};
  const auto single = reconstruct_depth(transport, rig, "true rig", DepthOptions{}, one, programs);
  const auto both = reconstruct_depth(transport, rig, "true rig", DepthOptions{}, devices, programs);
  ASSERT_GT(single.summary.at("reconstructed_pixels").get<int>(), 0);
  EXPECT_TRUE(same_bits(single.maps.depth_mm, both.maps.depth_mm));
  EXPECT_TRUE(same_bits(single.maps.normals, both.maps.normals));
  // Both devices delivered rows of the row solvers (otherwise the comparison above would prove nothing).
  for (const auto& report : both.summary.at("scheduler")) {
    if (report.at("stage") != "integrate" && report.at("stage") != "fuse") continue;
    for (const auto& device : report.at("devices")) EXPECT_GT(device.at("items").get<int>(), 0) << report.dump();
  }
}

}  // namespace
}  // namespace rfrecon::depth
