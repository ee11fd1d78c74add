// `rfrecon capture` end to end on the simulated rig (labels capture and accuracy: minutes under the sanitizers): the
// cube captured through the command reconstructs as well as the simulator's own capture of it (`simulate`, the same
// scene and noise model), board poses captured with --poses calibrate the rig, HDR beats one exposure where it
// saturates, and Ctrl-C mid-capture leaves nothing.
#include <cmath>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iterator>
#include <string>
#include <utility>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <sys/wait.h>

#include "calib/rig.h"
#include "sim/builtin_scenes.h"
#include "sim/truth_io.h"
#include "tests/common/run_cli.h"
#include "tests/common/temp_dir.h"

namespace rfrecon {
namespace {

namespace fs = std::filesystem;
using testing::run_cli;

// The fused reconstruction's RMS depth error on the object (mm) of the T.h5 `transport`, against the scene's truth.
double object_rms_mm(const fs::path& transport, const fs::path& truth, const fs::path& out) {
  const auto reconstruct = run_cli("reconstruct " + transport.string() + " --calib " + (truth / "rig.yaml").string() +
                                   " --method fused -o " + out.string());
  EXPECT_EQ(reconstruct.exit_code, 0) << reconstruct.output;
  const auto evaluate = run_cli("evaluate " + out.string() + " --truth " + truth.string());
  EXPECT_EQ(evaluate.exit_code, 0) << evaluate.output;
  std::ifstream file(out / "evaluation.json");
  const auto report = nlohmann::json::parse(file);
  return report.at("object_pixels").at("depth_error_mm").at("rms").get<double>();
}

TEST(CaptureEndToEnd, CubeCapturedThroughTheCommandReconstructsLikeTheSimulatorsCapture) {
  testing::TempDir dir("capture_cube");
  const fs::path scene = dir.path() / "simulated_scene";
  const auto simulate = run_cli("simulate --scene cube-anisotropic -o " + scene.string());
  ASSERT_EQ(simulate.exit_code, 0) << simulate.output;
  const auto simulated_transport =
      run_cli("transport " + (scene / "capture").string() + " -o " + (scene / "T.h5").string());
  ASSERT_EQ(simulated_transport.exit_code, 0) << simulated_transport.output;
  const auto capture = run_cli("capture --camera sim:cube-anisotropic -o " + (dir.path() / "capture").string());
  ASSERT_EQ(capture.exit_code, 0) << capture.output;
  const auto transport =
      run_cli("transport " + (dir.path() / "capture").string() + " -o " + (dir.path() / "T.h5").string());
  ASSERT_EQ(transport.exit_code, 0) << transport.output;
  const double captured = object_rms_mm(dir.path() / "T.h5", scene / "truth", dir.path() / "captured");
  const double simulated = object_rms_mm(scene / "T.h5", scene / "truth", dir.path() / "simulated");
  std::printf("fused RMS on the cube: %.4f mm captured, %.4f mm simulated\n", captured, simulated);
  EXPECT_LE(captured, 1.5 * simulated);
}

// Four of checkerboard-poses' views captured with --poses, then `rfrecon calibrate` on them as docs/capture.md says:
// the rig comes out within 0.1 % of the simulator's in focal lengths and baseline, reprojected under 0.1 px.
TEST(CaptureEndToEnd, PosesCapturedThroughTheCommandCalibrateTheRig) {
  testing::TempDir dir("capture_poses_calibrate");
  const auto capture = run_cli("-q capture --camera sim:checkerboard-poses --poses 4 --pose-wait 0 -o " +
                               (dir.path() / "poses").string());
  ASSERT_EQ(capture.exit_code, 0) << capture.output;
  const fs::path rig_file = dir.path() / "rig.yaml";
  const auto calibrate = run_cli("calibrate " + (dir.path() / "poses").string() +
                                 "/pose_* --board 14x9 --square 20 -o " + rig_file.string());
  ASSERT_EQ(calibrate.exit_code, 0) << calibrate.output;
  const calib::StereoRig rig = calib::read_rig(rig_file);
  const calib::StereoRig truth = sim::true_rig(sim::builtin_scene("checkerboard-poses"));
  const auto relative = [](double estimated, double true_value) { return std::abs(estimated / true_value - 1.0); };
  EXPECT_LT(rig.rms, 0.1);
  EXPECT_LT(relative(rig.camera_matrix.at<double>(0, 0), truth.camera_matrix.at<double>(0, 0)), 0.001);
  EXPECT_LT(relative(rig.camera_matrix.at<double>(1, 1), truth.camera_matrix.at<double>(1, 1)), 0.001);
  EXPECT_LT(relative(rig.projector_matrix.at<double>(0, 0), truth.projector_matrix.at<double>(0, 0)), 0.001);
  EXPECT_LT(relative(rig.projector_matrix.at<double>(1, 1), truth.projector_matrix.at<double>(1, 1)), 0.001);
  EXPECT_LT(relative(cv::norm(rig.proj_from_cam_translation_mm), cv::norm(truth.proj_from_cam_translation_mm)), 0.001);
  std::printf(
      "4 captured poses: RMS %.4f px, camera fx %.2f (true %.2f), projector fx %.2f (true %.2f), baseline "
      "%.3f mm (true %.3f)\n",
      rig.rms, rig.camera_matrix.at<double>(0, 0), truth.camera_matrix.at<double>(0, 0),
      rig.projector_matrix.at<double>(0, 0), truth.projector_matrix.at<double>(0, 0),
      cv::norm(rig.proj_from_cam_translation_mm), cv::norm(truth.proj_from_cam_translation_mm));
}

// The object's figures of `evaluate` (coverage %, RMS mm) for a reconstruction, on the pixels every one of `others`
// reconstructed too when given.
std::pair<double, double> object_figures(const fs::path& reconstruction, const fs::path& truth,
                                         const std::string& others, const fs::path& report) {
  const auto evaluate = run_cli("evaluate " + reconstruction.string() + " --truth " + truth.string() +
                                (others.empty() ? "" : " --same-pixels-as " + others) + " -o " + report.string() +
                                " --error-map " + report.string() + ".png");
  EXPECT_EQ(evaluate.exit_code, 0) << evaluate.output;
  std::ifstream file(report);
  const auto object = nlohmann::json::parse(file).at("object_pixels");
  return {object.at("coverage_percent").get<double>(), object.at("depth_error_mm").at("rms").get<double>()};
}

TEST(CaptureEndToEnd, HdrRaisesCoverageAndLowersErrorWhereOneExposureSaturates) {
  testing::TempDir dir("capture_hdr_sphere");
  const fs::path scene = dir.path() / "scene";
  ASSERT_EQ(run_cli("simulate --scene sphere-ward -o " + scene.string()).exit_code, 0);
  // At 40 ms the Ward sphere's highlight and much of its face saturate; 10 ms + 40 ms keeps both ends.
  for (const char* exposures : {"40000", "10000,40000"}) {
    const fs::path capture = dir.path() / (std::string("capture_") + exposures);
    const auto run =
        run_cli(std::string("capture --camera sim:sphere-ward --exposures ") + exposures + " -o " + capture.string());
    ASSERT_EQ(run.exit_code, 0) << run.output;
    ASSERT_EQ(run_cli("transport " + capture.string() + " -o " + capture.string() + ".h5").exit_code, 0);
    const auto reconstruct = run_cli("reconstruct " + capture.string() + ".h5 --calib " +
                                     (scene / "truth" / "rig.yaml").string() + " -o " + capture.string() + "_out");
    ASSERT_EQ(reconstruct.exit_code, 0) << reconstruct.output;
  }
  const fs::path single = dir.path() / "capture_40000_out";
  const fs::path hdr = dir.path() / "capture_10000,40000_out";
  const auto single_all = object_figures(single, scene / "truth", "", dir.path() / "single.json");
  const auto hdr_all = object_figures(hdr, scene / "truth", "", dir.path() / "hdr.json");
  const auto single_same = object_figures(single, scene / "truth", hdr.string(), dir.path() / "single_same.json");
  const auto hdr_same = object_figures(hdr, scene / "truth", single.string(), dir.path() / "hdr_same.json");
  std::printf("sphere-ward coverage %.1f %% -> %.1f %% with HDR; RMS on the same pixels %.4f -> %.4f mm\n",
              single_all.first, hdr_all.first, single_same.second, hdr_same.second);
  EXPECT_EQ(single_same.first, hdr_same.first) << "both evaluated on the same pixels";
  EXPECT_GT(hdr_all.first, 1.5 * single_all.first);
  EXPECT_LT(hdr_same.second, single_same.second);
}

TEST(CaptureEndToEnd, InterruptedCaptureLeavesNothing) {
  testing::TempDir dir("capture_interrupt");
  testing::TempDir work("capture_interrupt_log");
  // SIGINT once the latency is measured and frames are being captured (waiting up to 5 min: a loaded machine renders
  // the cube slowly).
  const fs::path script = work.path() / "interrupt.sh";
  std::ofstream(script) << RFRECON_CLI_PATH << " capture --camera sim:cube-anisotropic -o "
                        << (dir.path() / "capture").string() << " > " << (work.path() / "log").string()
                        << " 2>&1 &\npid=$!\nfor i in $(seq 6000); do grep -q 'sees a pattern' "
                        << (work.path() / "log").string() << " && break; sleep 0.05; done\n"
                        << "kill -INT $pid\nwait $pid\nexit $?\n";
  const int status = std::system(("sh " + script.string()).c_str());
  std::ifstream log(work.path() / "log");
  const std::string output((std::istreambuf_iterator<char>(log)), std::istreambuf_iterator<char>());
  EXPECT_EQ(WEXITSTATUS(status), 128 + SIGINT) << output;
  EXPECT_NE(output.find("sees a pattern"), std::string::npos) << output;
  EXPECT_TRUE(fs::is_empty(dir.path())) << "a partial capture or a temporary was left";
}

}  // namespace
}  // namespace rfrecon
