// The capture run on the simulated rig: the latency is measured to the frame, every frame shows the pattern it
// should, and injected late or repeated frames are captured again and reported, never written silently.
#include "host/acquire/capture_run.h"

#include <cmath>

#include <gtest/gtest.h>

#include "host/acquire/latency.h"
#include "host/core/errors.h"
#include "sim/frames.h"
#include "sim/simulated_rig.h"
#include "tests/common/temp_dir.h"
#include "tests/sim/test_scenes.h"

namespace rfrecon::acquire {
namespace {

namespace st = sim::testing;

sim::Scene test_scene() {
  sim::Scene scene = st::make_scene(st::small_rig({st::tilted_plane(st::kLambert)}));
  scene.capture.dot_spacing = 4;
  scene.capture.ambient = 0.01;
  return scene;
}

CaptureRunOptions scan_options() {
  CaptureRunOptions options;
  options.protocol.dot_spacing = 4;
  return options;
}

// RMS over the camera of each captured frame's linear reading minus the noise-free render of its pattern: at most
// `tolerance` (about three times the noise) when the camera saw the pattern it meant.
void expect_frames_show_their_patterns(const std::filesystem::path& dir, const sim::Scene& scene) {
  const auto manifest = capture::read_manifest(dir);
  const auto T = sim::render_transport(scene).T;
  const double tolerance = 0.02;
  for (std::size_t i = 0; i < manifest.frames.size(); ++i) {
    const cv::Mat frame = capture::load_frame(dir, manifest, i);
    const cv::Mat pattern = capture::render_pattern(manifest.frames[i].pattern, capture::protocol_options(manifest));
    const cv::Mat expected = sim::transport_image(T, pattern, scene.camera.size) + scene.capture.ambient;
    const double rms = cv::norm(frame, expected, cv::NORM_L2) / std::sqrt(static_cast<double>(frame.total()));
    EXPECT_LT(rms, tolerance) << manifest.frames[i].file;
  }
}

TEST(Latency, MeasuredToTheFrame) {
  for (int lag : {0, 1, 2, 5}) {
    sim::SimulatedRig rig(test_scene(), {lag, {}, {}});
    EXPECT_EQ(measure_latency_frames(rig.projector(), rig.camera()), lag) << "display lag " << lag;
  }
}

TEST(Latency, ACameraThatDoesNotSeeTheProjectorIsAHardwareError) {
  sim::Scene scene = test_scene();
  scene.objects.clear();  // nothing reflects the projector's light
  sim::SimulatedRig rig(scene);
  try {
    measure_latency_frames(rig.projector(), rig.camera());
    FAIL() << "no error";
  } catch (const HardwareError& error) {
    EXPECT_NE(std::string(error.what()).find("does not see"), std::string::npos) << error.what();
  }
}

TEST(CaptureRun, LaggingDisplayIsWaitedOutAndEveryFrameShowsItsPattern) {
  const sim::Scene scene = test_scene();
  sim::SimulatedRig rig(scene, {3, {}, {}});
  testing::TempDir dir("capture_lag");
  const auto report = capture_scan(rig.projector(), rig.camera(), scan_options(), dir.path() / "scan", false);
  EXPECT_EQ(report.latency_frames, 3);
  EXPECT_EQ(report.recaptured_pairs, 0u);
  EXPECT_EQ(report.repeated_frames, 0u);
  EXPECT_EQ(report.grabs, report.manifest.frames.size() * 4);
  expect_frames_show_their_patterns(dir.path() / "scan", scene);
}

TEST(CaptureRun, LateFrameIsReportedAndItsPairCapturedAgain) {
  const sim::Scene scene = test_scene();
  // Shows 0..5 are the latency's three flashes; show 6 + 4 is the first column bit's inverse... any Gray show will
  // do: shows 6 and 7 are white and black, 8 onwards the Gray pairs.
  sim::SimulatedRig rig(scene, {1, {11}, {}});
  testing::TempDir dir("capture_late");
  const auto report = capture_scan(rig.projector(), rig.camera(), scan_options(), dir.path() / "scan", false);
  EXPECT_EQ(report.recaptured_pairs, 1u);
  expect_frames_show_their_patterns(dir.path() / "scan", scene);
}

TEST(CaptureRun, RepeatedBufferIsReportedAndGrabbedAgain) {
  const sim::Scene scene = test_scene();
  CaptureRunOptions options = scan_options();
  options.latency_frames = 0;
  sim::SimulatedRig rig(scene, {0, {}, {20, 40}});
  testing::TempDir dir("capture_repeat");
  const auto report = capture_scan(rig.projector(), rig.camera(), options, dir.path() / "scan", false);
  EXPECT_EQ(report.repeated_frames, 2u);
  expect_frames_show_their_patterns(dir.path() / "scan", scene);
}

TEST(CaptureRun, LatencyTooShortFailsAndWritesNothing) {
  CaptureRunOptions options = scan_options();
  options.latency_frames = 0;  // the display lags by 2: every frame shows the pattern before last
  sim::SimulatedRig rig(test_scene(), {2, {}, {}});
  testing::TempDir dir("capture_short");
  try {
    capture_scan(rig.projector(), rig.camera(), options, dir.path() / "scan", false);
    FAIL() << "no error";
  } catch (const HardwareError& error) {
    EXPECT_NE(std::string(error.what()).find("shown late"), std::string::npos) << error.what();
  }
  EXPECT_TRUE(std::filesystem::is_empty(dir.path()));
}

TEST(CaptureRun, BlackLevelGivenReplacesTheCamerasAndIsChecked) {
  CaptureRunOptions options = scan_options();
  options.black_level_dn = 12.0;
  sim::SimulatedRig rig(test_scene());
  testing::TempDir dir("capture_black");
  capture_scan(rig.projector(), rig.camera(), options, dir.path() / "scan", false);
  EXPECT_EQ(capture::read_manifest(dir.path() / "scan").black_level, 12.0);
  options.black_level_dn = 1023.0;  // the 10-bit camera's top code: no span left
  EXPECT_THROW(capture_scan(rig.projector(), rig.camera(), options, dir.path() / "bad", false), InputError);
  EXPECT_FALSE(std::filesystem::exists(dir.path() / "bad"));
}

TEST(CaptureRun, DisplaySmallerThanTheProjectorSizeIsAUsageError) {
  CaptureRunOptions options = scan_options();
  options.protocol.projector_size = {160, 60};
  sim::SimulatedRig rig(test_scene());
  testing::TempDir dir("capture_small");
  EXPECT_THROW(capture_scan(rig.projector(), rig.camera(), options, dir.path() / "scan", false), UsageError);
  EXPECT_TRUE(std::filesystem::is_empty(dir.path()));
}

TEST(CaptureRun, SeveralExposuresAreMergedAndRecordedInTheManifest) {
  const sim::Scene scene = test_scene();
  CaptureRunOptions options = scan_options();
  options.exposures_us = {5000.0, 10000.0, 20000.0};
  sim::SimulatedRig rig(scene);
  testing::TempDir dir("capture_hdr");
  const auto report = capture_scan(rig.projector(), rig.camera(), options, dir.path() / "scan", false);
  const auto manifest = capture::read_manifest(dir.path() / "scan");
  EXPECT_EQ(manifest.bit_depth, 16);
  EXPECT_EQ(manifest.black_level, 0.0);
  EXPECT_EQ(manifest.exposures_us, options.exposures_us);
  // Merged frames are in units of the shortest exposure (half the reference): the render scaled by 0.5.
  const auto T = sim::render_transport(scene).T;
  const cv::Mat white(scene.projector.size, CV_8UC1, cv::Scalar(255));
  const cv::Mat expected = 0.5 * (sim::transport_image(T, white, scene.camera.size) + scene.capture.ambient);
  const cv::Mat frame = capture::load_frame(dir.path() / "scan", manifest, 0);
  EXPECT_LT(cv::norm(frame, expected, cv::NORM_L2) / std::sqrt(static_cast<double>(frame.total())), 0.01);
}

TEST(CapturePoses, OneDirectoryPerPoseAfterEachWait) {
  sim::SimulatedRig rig(test_scene());
  testing::TempDir dir("capture_poses");
  std::vector<int> waited;
  const auto reports = capture_poses(
      rig.projector(), rig.camera(), scan_options(), 2, [&](int pose) { waited.push_back(pose); }, dir.path() / "poses",
      false);
  EXPECT_EQ(reports.size(), 2u);
  EXPECT_EQ(waited, (std::vector<int>{0, 1}));
  for (const char* pose : {"pose_01", "pose_02"}) {
    EXPECT_NO_THROW(capture::read_manifest(dir.path() / "poses" / pose)) << pose;
  }
}

}  // namespace
}  // namespace rfrecon::acquire
