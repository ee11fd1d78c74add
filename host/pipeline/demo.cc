// The demo: simulate, calibrate, transport, reconstruct and evaluate, composed from the library's calls.
#include "host/pipeline/demo.h"

#include <chrono>

#include <nlohmann/json.hpp>
#include <spdlog/spdlog.h>

#include "calib/camera_from_images.h"
#include "host/core/atomic_file.h"
#include "host/core/output_path.h"
#include "host/depth/depth_method.h"
#include "host/evaluation/evaluation.h"
#include "host/pipeline/calibrate_rig.h"
#include "host/pipeline/reconstruct_scan.h"
#include "host/pipeline/transport_capture.h"
#include "sim/builtin_rigs.h"
#include "sim/builtin_scenes.h"
#include "sim/simulate.h"

namespace rfrecon::pipeline {

namespace fs = std::filesystem;

namespace {
constexpr const char* kPosesScene = "checkerboard-poses";
constexpr const char* kObjectScene = "cube-anisotropic";

void render(const std::string& scene, const std::string& rig, const fs::path& out_dir) {
  spdlog::info("demo: render {} on the {} rig into {}", scene, rig, out_dir.string());
  sim::simulate(sim::resolve_scene(scene, rig), out_dir, {0, true, {}});
}

std::vector<fs::path> pose_dirs(const fs::path& rendering) {
  std::vector<fs::path> dirs;
  for (int pose = 0;; ++pose) {
    const fs::path dir = rendering / "capture" / fmt::format("pose_{:02d}", pose);
    if (!fs::exists(dir)) break;
    dirs.push_back(dir);
  }
  return dirs;
}
}  // namespace

DemoRun run_demo(const fs::path& out_dir, const std::string& rig, bool force, std::vector<cl::DeviceContext>& devices,
                 cl::ProgramCache& programs) {
  check_output_directory({out_dir, "--output", force}, {});
  const auto start = std::chrono::steady_clock::now();
  DemoRun demo;
  demo.scene = kObjectScene;
  demo.rig = rig.empty() ? sim::kDefaultRig : rig;
  demo.out_dir = out_dir;
  const fs::path poses = out_dir / kPosesScene, cube = out_dir / kObjectScene;

  render(kPosesScene, demo.rig, poses);
  RigCalibrationRequest calibration;
  calibration.pose_dirs = pose_dirs(poses);
  calibration.board = {14, 9, 20.0};
  calibration.output = out_dir / "rig.yaml";
  calibration.report_dir = calib::default_report_dir(calibration.output);
  calibration.force = true;
  spdlog::info("demo: calibrate camera and projector from {} poses", calibration.pose_dirs.size());
  const auto calibrated = calibrate_rig(calibration, devices, programs);
  spdlog::info("demo: stereo reprojection RMS {:.4f} px over {} poses", calibrated.calibration.rig.rms,
               calibrated.view_names.size());

  render(kObjectScene, demo.rig, cube);
  TransportRequest transport;
  transport.capture_dir = cube / "capture";
  transport.output = cube / "T.h5";
  transport.force = true;
  spdlog::info("demo: light transport of {}", transport.capture_dir.string());
  transport_capture(transport, devices, programs);

  const auto truth = evaluation::read_evaluation_truth(cube);
  nlohmann::json table = nlohmann::json::array();
  for (const std::string& method : depth::depth_method_names()) {
    ReconstructRequest reconstruct;
    reconstruct.transport = transport.output;
    reconstruct.rig = calibration.output;
    reconstruct.depth.method = method;
    reconstruct.out_dir = out_dir / method;
    reconstruct.force = true;
    spdlog::info("demo: reconstruct ({})", method);
    const auto run = reconstruct_scan(reconstruct, devices, programs);
    // The maps in memory equal those just written (float32 TIFFs), so the truth is read once and nothing read back.
    const auto e = evaluation::evaluate(run.depth.maps, truth, (reconstruct.out_dir / "depth.tiff").string());
    evaluation::write_evaluation(e, reconstruct.out_dir / "evaluation.json", reconstruct.out_dir / "error_map.png");
    demo.object_size_mm = e.object_size_mm;
    DemoRow row{method,
                e.object.rms_mm,
                100.0 * e.object.rms_mm / e.object_size_mm,
                e.object.mean_abs_mm,
                e.object.max_abs_mm,
                e.object.coverage_percent};
    demo.methods.push_back(row);
    table.push_back({{"method", row.method},
                     {"rms_mm", row.rms_mm},
                     {"rms_percent", row.rms_percent},
                     {"mean_abs_mm", row.mean_abs_mm},
                     {"max_abs_mm", row.max_abs_mm},
                     {"coverage_percent", row.coverage_percent},
                     {"object_size_mm", e.object_size_mm}});
  }
  demo.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  write_file_atomically(out_dir / "demo.json", nlohmann::json{{"scene", demo.scene},
                                                              {"rig", demo.rig},
                                                              {"calibration", calibration.output.string()},
                                                              {"seconds", demo.seconds},
                                                              {"methods", table}}
                                                   .dump(2));
  return demo;
}

}  // namespace rfrecon::pipeline
