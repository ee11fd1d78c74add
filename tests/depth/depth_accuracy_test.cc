// Depth accuracy end to end on the synthetic rig: the built-in scenes rendered with 10-bit noise, T built by the
// transport stage, the rig calibrated from the rendered checkerboard poses (not the true calibration), then
// triangulation, reciprocity integration and fusion compared with the ground truth in % of the object's size.
#include <filesystem>
#include <map>
#include <string>

#include <gtest/gtest.h>

#include "calib/rig.h"
#include "host/cl/device_selection.h"
#include "host/depth/reconstruct_depth.h"
#include "host/evaluation/evaluation.h"
#include "host/transport/transport_file.h"

namespace rfrecon::depth {
namespace {

namespace fs = std::filesystem;
const fs::path kFixtures(RFRECON_FIXTURES_DIR);
const fs::path kEstimatedRig = kFixtures / "checkerboard-poses" / "estimated" / "rig.yaml";

// RMS depth error of the scene's subject in % of its size, per method.
std::map<Method, double> rms_percent(const std::string& scene, const fs::path& rig_file) {
  const auto transport = transport::read_transport(kFixtures / scene / "T.h5");
  const auto rig = calib::read_rig(rig_file);
  const auto truth = evaluation::read_evaluation_truth(kFixtures / scene);
  auto devices = cl::open_devices("all");
  cl::ProgramCache programs;
  std::map<Method, double> result;
  for (const Method method : {Method::kTriangulate, Method::kIntegrate, Method::kFused}) {
    DepthOptions options;
    options.method = method;
    const auto run = reconstruct_depth(transport, rig, rig_file.string(), options, devices, programs);
    const auto evaluation = evaluation::evaluate(run.maps, truth);
    // Every method must cover at least half of the subject (the cylinder's saturated highlight is masked): the masks
    // may not buy accuracy by dropping most pixels.
    EXPECT_GT(evaluation.object.coverage_percent, 50.0) << scene << " " << method_name(method);
    result[method] = 100.0 * evaluation.object.rms_mm / evaluation.object_size_mm;
    std::printf("%s %s %s: RMS %.4f mm = %.3f %% of %.0f mm, coverage %.1f %%\n", scene.c_str(),
                rig_file.parent_path().filename().c_str(), method_name(method).c_str(), evaluation.object.rms_mm,
                result[method], evaluation.object_size_mm, evaluation.object.coverage_percent);
  }
  return result;
}

TEST(DepthAccuracy, CubeWithEstimatedCalibration) {
  // Measured 0.33 % (triangulate), 0.35 % (integrate), 0.25 % (fused): fused better than both. The fused error is
  // almost all a bias of the estimated calibration (0.146 mm of its 0.151 mm RMS; with the true rig it is 0.076 %),
  // which changes from one calibration to the next: limits 0.3 % and 0.5 %
  // (docs/accuracy.md).
  const auto rms = rms_percent("cube-anisotropic", kEstimatedRig);
  EXPECT_LE(rms.at(Method::kFused), 0.3);
  EXPECT_LT(rms.at(Method::kFused), rms.at(Method::kTriangulate));
  EXPECT_LT(rms.at(Method::kFused), rms.at(Method::kIntegrate));
  EXPECT_LE(rms.at(Method::kIntegrate), 0.5);
}

TEST(DepthAccuracy, CubeWithTrueCalibrationMeetsThePaperAndTheFusionTarget) {
  // Without calibration error: integrate (the paper's method) within the paper's 0.3 %, fused within 0.1 %
  // (measured 0.26 % and 0.076 %).
  const auto rms = rms_percent("cube-anisotropic", kFixtures / "cube-anisotropic" / "truth" / "rig.yaml");
  EXPECT_LE(rms.at(Method::kIntegrate), 0.3);
  EXPECT_LE(rms.at(Method::kFused), 0.1);
}

TEST(DepthAccuracy, FusionBeatsTriangulationOnCurvedShinyObjects) {
  // sphere-ward and cylinder-brushed (saturated highlights, dropped by the saturation mask).
  for (const std::string scene : {"sphere-ward", "cylinder-brushed"}) {
    const auto rms = rms_percent(scene, kEstimatedRig);
    EXPECT_LT(rms.at(Method::kFused), rms.at(Method::kTriangulate)) << scene;
  }
}

}  // namespace
}  // namespace rfrecon::depth
