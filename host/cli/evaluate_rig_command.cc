// `rfrecon evaluate-rig`: an estimated rig (from `calibrate`) against the true rig of `rfrecon simulate`, and
// optionally the corners that `calibrate` found against the rendered board's true corners.
#include <cstdio>

#include <nlohmann/json.hpp>

#include "calib/corner_comparison.h"
#include "calib/rig_comparison.h"
#include "host/cli/commands.h"
#include "host/core/atomic_file.h"
#include "host/core/errors.h"
#include "host/core/output_path.h"

namespace rfrecon::cli {

namespace {
struct EvaluateRigOptions {
  std::filesystem::path estimated;
  std::filesystem::path truth;
  std::filesystem::path corners;      // calibrate's report: corners.json
  std::filesystem::path board_poses;  // simulate's truth: board_poses.json
  std::filesystem::path output;
  bool force = false;
};

nlohmann::json corner_errors_json(const calib::CornerErrors& e) {
  return {{"rms_px", e.rms_px}, {"mean_x_px", e.mean_px.x}, {"mean_y_px", e.mean_px.y}, {"max_px", e.max_px}};
}

void run_evaluate_rig(const EvaluateRigOptions& options) {
  if (options.corners.empty() != options.board_poses.empty()) {
    throw UsageError("--corners and --board-poses go together");
  }
  if (!options.output.empty()) {
    check_output_file({options.output, "--output", options.force},
                      {options.estimated, options.truth, options.corners, options.board_poses});
  }
  const auto truth = calib::read_rig(options.truth);
  const auto c = calib::compare_rigs(calib::read_rig(options.estimated), truth);
  const auto views = options.corners.empty() ? std::vector<calib::ViewCorners>{}
                                             : calib::read_view_corners(options.corners, options.board_poses);
  std::printf("camera     focal %.4f%%  principal point %.3f px\n", 100.0 * c.camera_focal_error,
              c.camera_principal_error_px);
  std::printf("projector  focal %.4f%%  principal point %.3f px\n", 100.0 * c.projector_focal_error,
              c.projector_principal_error_px);
  std::printf("baseline   %+.5f%%  rotation %.4f degree\n", 100.0 * c.baseline_error, c.rotation_error_deg);
  std::printf("depth      scale error %+.2e  RMS %.2e over %d points at 500 to 700 mm\n", c.depth_scale_error,
              c.depth_rms_error, c.points);
  nlohmann::json corners = nlohmann::json::object();
  if (!options.corners.empty()) {
    const auto e = calib::compare_corners(views, truth);
    for (const auto& [device, errors] : {std::pair{"camera", e.camera}, std::pair{"projector", e.projector}}) {
      std::printf("%-10s corners RMS %.4f px per axis, mean (%+.4f, %+.4f) px, max %.3f px over %d\n", device,
                  errors.rms_px, errors.mean_px.x, errors.mean_px.y, errors.max_px, errors.corners);
      corners[std::string(device) + "_corners"] = corner_errors_json(errors);
    }
  }
  if (options.output.empty()) return;
  nlohmann::json report = {{"estimated", options.estimated.string()},
                           {"truth", options.truth.string()},
                           {"camera_focal_error", c.camera_focal_error},
                           {"camera_principal_error_px", c.camera_principal_error_px},
                           {"projector_focal_error", c.projector_focal_error},
                           {"projector_principal_error_px", c.projector_principal_error_px},
                           {"baseline_error", c.baseline_error},
                           {"rotation_error_deg", c.rotation_error_deg},
                           {"depth_scale_error", c.depth_scale_error},
                           {"depth_rms_error", c.depth_rms_error},
                           {"points", c.points}};
  report.update(corners);
  write_file_atomically(options.output, report.dump(2) + "\n");
}
}  // namespace

void add_evaluate_rig_command(CLI::App& app) {
  auto options = std::make_shared<EvaluateRigOptions>();
  auto* command = app.add_subcommand("evaluate-rig", "Compare a calibrated rig.yaml with the true rig of `simulate`");
  command->add_option("estimated", options->estimated, "Rig file written by `rfrecon calibrate`")->required();
  command->add_option("--truth", options->truth, "True rig file (SIMULATE_OUT/truth/rig.yaml)")->required();
  command->add_option("--corners", options->corners, "Also compare the corners found (CALIBRATE_REPORT/corners.json)");
  command->add_option("--board-poses", options->board_poses,
                      "with the true ones (SIMULATE_OUT/truth/board_poses.json)");
  command->add_option("-o,--output", options->output, "Also write the comparison as JSON");
  command->add_flag("--force", options->force, "Replace an existing JSON file");
  command->callback([options] { run_evaluate_rig(*options); });
}

}  // namespace rfrecon::cli
