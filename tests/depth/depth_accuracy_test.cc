// Depth accuracy end to end on the synthetic rigs: the built-in scenes rendered with 10-bit noise, T built by the
// transport stage, the rig calibrated from the rendered checkerboard poses (not the true calibration), then
// triangulation, reciprocity integration and fusion compared with the ground truth in % of the object's size, every
// method over the same pixels (those of the object that all three reconstruct). The default rig has the projector
// above the camera and devices of different sizes; the side-by-side rig is the earlier 640x480 pair.
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>
#include <string>

#include <gtest/gtest.h>

#include "calib/rig.h"
#include "host/cl/device_selection.h"
#include "host/core/errors.h"
#include "host/depth/reconstruct_depth.h"
#include "host/evaluation/evaluation.h"
#include "host/transport/transport_file.h"

namespace rfrecon::depth {
namespace {

namespace fs = std::filesystem;
const fs::path kFixtures(RFRECON_FIXTURES_DIR);
const fs::path kEstimatedRig = kFixtures / "checkerboard-poses" / "estimated" / "rig.yaml";
const fs::path kSideBySide = kFixtures / "side-by-side";
const fs::path kSideBySideRig = kSideBySide / "checkerboard-poses" / "estimated" / "rig.yaml";

// RMS depth error of the scene's subject in % of its size, over the object pixels every method reconstructs, per
// method; each method must also cover at least half of the object on its own (the masks may not buy accuracy by
// dropping most pixels).
std::map<std::string, double> rms_percent(const fs::path& scene_dir, const fs::path& rig_file) {
  const auto transport = transport::read_transport(scene_dir / "T.h5");
  const auto rig = calib::read_rig(rig_file);
  const auto truth = evaluation::read_evaluation_truth(scene_dir);
  auto devices = cl::open_devices("all");
  cl::ProgramCache programs;
  std::map<std::string, evaluation::Evaluation> evaluations;
  cv::Mat common;
  for (const std::string method : {"triangulate", "integrate", "fused"}) {
    DepthOptions options;
    options.method = method;
    const auto run = reconstruct_depth(transport, rig, rig_file.string(), options, devices, programs);
    auto evaluation = evaluation::evaluate(run.maps, truth);
    EXPECT_GT(evaluation.object.coverage_percent, 50.0) << scene_dir << " " << method;
    const cv::Mat reconstructed = evaluation.depth_error_mm == evaluation.depth_error_mm;  // not NaN
    common = common.empty() ? (evaluation.object_mask & reconstructed) : (common & reconstructed);
    evaluations.emplace(method, std::move(evaluation));
  }
  std::map<std::string, double> result;
  EXPECT_GT(cv::countNonZero(common), 0);
  for (const auto& [method, evaluation] : evaluations) {
    cv::Scalar mean_mm, std_mm;
    cv::meanStdDev(evaluation.depth_error_mm, mean_mm, std_mm, common);
    const double rms_mm = std::hypot(mean_mm[0], std_mm[0]);
    result[method] = 100.0 * rms_mm / evaluation.object_size_mm;
    std::printf(
        "%s with %s, %s: RMS %.4f mm = %.3f %% of %.0f mm (bias %+.4f mm) on %d common pixels (own coverage "
        "%.1f %%)\n",
        scene_dir.filename().c_str(), rig_file.string().c_str(), method.c_str(), rms_mm, result[method],
        evaluation.object_size_mm, mean_mm[0], cv::countNonZero(common), evaluation.object.coverage_percent);
  }
  return result;
}

TEST(DepthAccuracy, CubeOnTheDefaultRigWithEstimatedCalibration) {
  // The targets for this rig (projector above, unequal sizes), calibrated from its rendered poses: at least
  // the side-by-side rig's earlier figures, fused better than both. Measured 0.062 % (fused), 0.120 % (integrate),
  // 0.125 % (triangulate) on the same pixels.
  const auto rms = rms_percent(kFixtures / "cube-anisotropic", kEstimatedRig);
  EXPECT_LE(rms.at("fused"), 0.25);
  EXPECT_LE(rms.at("integrate"), 0.35);
  EXPECT_LE(rms.at("triangulate"), 0.34);
  EXPECT_LT(rms.at("fused"), rms.at("triangulate"));
  EXPECT_LT(rms.at("fused"), rms.at("integrate"));
}

TEST(DepthAccuracy, CubeOnTheDefaultRigWithTrueCalibration) {
  const auto rms = rms_percent(kFixtures / "cube-anisotropic", kFixtures / "cube-anisotropic" / "truth" / "rig.yaml");
  EXPECT_LE(rms.at("fused"), 0.05);
  EXPECT_LE(rms.at("integrate"), 0.3);  // the paper's figure for its method
}

TEST(DepthAccuracy, CubeOnTheSideBySideRigWithEstimatedCalibration) {
  // The earlier rig's limits (docs/accuracy.md): fused within 0.3 % and better than both, integrate within 0.5 %
  // (measured 0.127 % and 0.258 %).
  const auto rms = rms_percent(kSideBySide / "cube-anisotropic", kSideBySideRig);
  EXPECT_LE(rms.at("fused"), 0.3);
  EXPECT_LT(rms.at("fused"), rms.at("triangulate"));
  EXPECT_LT(rms.at("fused"), rms.at("integrate"));
  EXPECT_LE(rms.at("integrate"), 0.5);
}

TEST(DepthAccuracy, CubeOnTheSideBySideRigWithTrueCalibration) {
  const auto rms =
      rms_percent(kSideBySide / "cube-anisotropic", kSideBySide / "cube-anisotropic" / "truth" / "rig.yaml");
  EXPECT_LE(rms.at("integrate"), 0.3);
  EXPECT_LE(rms.at("fused"), 0.1);
}

TEST(DepthAccuracy, GrayCodeOnlyCubeTriangulatesWithinHalfAPercent) {
  // No dot grid: triangulation from the sub-pixel Gray-code correspondences, with the rig calibrated from the
  // (dot-grid) poses.
  const fs::path scene = kFixtures / "cube-anisotropic-gray";
  const auto transport = transport::read_transport(scene / "T.h5");
  ASSERT_EQ(transport.setup.dot_spacing, 0);
  const auto rig = calib::read_rig(kEstimatedRig);
  const auto truth = evaluation::read_evaluation_truth(scene);
  auto devices = cl::open_devices("all");
  cl::ProgramCache programs;
  DepthOptions options;
  options.method = "triangulate";
  const auto run = reconstruct_depth(transport, rig, "rig.yaml", options, devices, programs);
  const auto evaluation = evaluation::evaluate(run.maps, truth);
  const double rms = 100.0 * evaluation.object.rms_mm / evaluation.object_size_mm;
  std::printf("Gray code only, triangulate: RMS %.4f mm = %.3f %%, coverage %.1f %%\n", evaluation.object.rms_mm, rms,
              evaluation.object.coverage_percent);
  EXPECT_LE(rms, 0.5);
  // Pixels on a code boundary decode between two codes (measured 83.7 to 83.8 % over seeds 1 to 3, docs/accuracy.md;
  // 69.4 % when they did not); boundary rejection is 2 px wide and the edge rule drops the pixels beside the cube's
  // shadow and silhouette: less coverage than with dots.
  EXPECT_GT(evaluation.object.coverage_percent, 78.0);
  // The reciprocity methods need the dot grid's full rows of T and say so.
  options.method = "fused";
  try {
    reconstruct_depth(transport, rig, "rig.yaml", options, devices, programs);
    ADD_FAILURE() << "fused ran on a Gray-code-only capture";
  } catch (const InputError& error) {
    EXPECT_NE(std::string(error.what()).find("dot-grid"), std::string::npos) << error.what();
  }
}

TEST(DepthAccuracy, FusionBeatsTriangulationOnCurvedShinyObjects) {
  // sphere-ward and cylinder-brushed (saturated highlights, dropped by the saturation mask), default rig.
  for (const std::string scene : {"sphere-ward", "cylinder-brushed"}) {
    const auto rms = rms_percent(kFixtures / scene, kEstimatedRig);
    EXPECT_LT(rms.at("fused"), rms.at("triangulate")) << scene;
  }
}

}  // namespace
}  // namespace rfrecon::depth
