// `rfrecon calibrate` (camera + projector through dual images, stereo pose, rectification) and
// `rfrecon calibrate-camera` (a camera alone from checkerboard photographs).
#include <cstdio>

#include "calib/camera_from_images.h"
#include "host/cl/device_selection.h"
#include "host/cli/capture_options.h"
#include "host/cli/commands.h"
#include "host/cli/number_checks.h"
#include "host/cli/size_option.h"
#include "host/core/errors.h"
#include "host/pipeline/calibrate_rig.h"

namespace rfrecon::cli {

namespace {
struct BoardOptions {
  std::string board;  // COLSxROWS inner corners
  double square_mm = 0.0;
  std::string distortion = "standard";
  bool refine_board = false;
};

calib::BoardSpec board_spec(const BoardOptions& options) {
  const cv::Size size = parse_size(options.board, "--board");
  if (size.width < 2 || size.height < 2) throw UsageError("--board needs at least 2x2 inner corners");
  if (size.width == size.height) {
    throw UsageError("--board " + options.board +
                     ": use a board whose inner corner counts differ (e.g. 9x6), so its orientation is unambiguous");
  }
  return {size.width, size.height, options.square_mm};
}

void add_board_options(CLI::App* command, BoardOptions& options) {
  command->add_option("--board", options.board, "Inner corners of the checkerboard, COLSxROWS (e.g. 9x6)")->required();
  command->add_option("--square", options.square_mm, "Side of one square, in mm")->required()->check(finite_positive());
  command
      ->add_option("--distortion", options.distortion,
                   "Lens model: radial (k1 k2), standard (k1 k2 p1 p2, default), full (+ k3, wide-angle lenses) "
                   "or rational (k1..k6 p1 p2)")
      ->check(CLI::IsMember({"radial", "standard", "full", "rational"}))
      ->capture_default_str();
  command->add_flag("--refine-board", options.refine_board,
                    "Also estimate the board's corner positions (a board not quite flat; needs 15 or more poses)");
}

calib::CalibrationOptions calibration_options(const BoardOptions& options) {
  calib::CalibrationOptions out;
  out.distortion = calib::parse_distortion_model(options.distortion, "--distortion");
  out.refine_board = options.refine_board;
  return out;
}

// The intrinsics with one standard deviation each, as Bouguet's toolbox prints them.
void print_intrinsics(const char* device, const cv::Mat& matrix, const cv::Mat& dist, const cv::Mat& intrinsics_std) {
  std::printf("%-10s fx %.2f +- %.2f  fy %.2f +- %.2f  cx %.2f +- %.2f  cy %.2f +- %.2f  k1 %.4f  k2 %.4f\n", device,
              matrix.at<double>(0, 0), intrinsics_std.at<double>(0), matrix.at<double>(1, 1),
              intrinsics_std.at<double>(1), matrix.at<double>(0, 2), intrinsics_std.at<double>(2),
              matrix.at<double>(1, 2), intrinsics_std.at<double>(3), dist.at<double>(0), dist.at<double>(1));
}

struct CameraOptions {
  std::vector<std::filesystem::path> images;
  BoardOptions board;
  std::filesystem::path output;
  std::filesystem::path report;
  bool force = false;
};

void run_calibrate_camera(const CameraOptions& options) {
  calib::CameraImagesRequest request;
  request.images = options.images;
  request.board = board_spec(options.board);
  request.options = calibration_options(options.board);
  request.output = options.output;
  request.report_dir = options.report.empty() ? calib::default_report_dir(options.output) : options.report;
  request.force = options.force;
  const auto run = calib::calibrate_camera_from_images(request);
  const auto& result = run.calibration;
  std::printf("%zu of %zu views used; reprojection RMS %.4f px\n", result.view_names.size(), run.images, result.rms);
  print_intrinsics("camera", result.camera_matrix, result.dist_coeffs, result.intrinsics_std);
  for (std::size_t i = 0; i < result.view_names.size(); ++i) {
    std::printf("  %-24s %.4f px\n", result.view_names[i].c_str(), result.per_view_errors[i]);
  }
  std::printf("wrote %s and %s/\n", request.output.c_str(), request.report_dir.c_str());
}

struct StereoOptions {
  std::vector<std::filesystem::path> poses;
  BoardOptions board;
  std::filesystem::path output;
  std::filesystem::path report;
  CaptureOptions capture;
  std::string devices;
  int dense_points = calib::CalibrationOptions{}.dense_points;
  bool no_gating = false;
  bool force = false;
};

void run_calibrate(const StereoOptions& options) {
  pipeline::RigCalibrationRequest request;
  request.pose_dirs = options.poses;
  request.source = capture_source(options.capture);
  request.board = board_spec(options.board);
  request.options = calibration_options(options.board);
  request.options.dense_points = options.dense_points;
  request.options.gating = !options.no_gating;
  request.output = options.output;
  request.report_dir = options.report.empty() ? calib::default_report_dir(options.output) : options.report;
  request.force = options.force;
  auto devices = cl::open_devices(options.devices);
  cl::ProgramCache programs;
  const auto run = pipeline::calibrate_rig(request, devices, programs);
  sched::log_reports(run.schedule);
  const auto& result = run.calibration;
  std::printf(
      "%zu of %zu poses used; stereo reprojection RMS %.4f px (%.4f px over every corner; %zu gating "
      "decisions)\n",
      run.view_names.size(), run.poses, result.rig.rms, result.rms_all_px, result.gating.size());
  const auto& rig = result.rig;
  print_intrinsics("camera", rig.camera_matrix, rig.dist_coeffs, rig.uncertainty.camera_intrinsics);
  print_intrinsics("projector", rig.projector_matrix, rig.projector_dist_coeffs, rig.uncertainty.projector_intrinsics);
  std::printf("baseline   %.3f mm  (T = [%.3f %.3f %.3f] +- [%.3f %.3f %.3f])\n",
              cv::norm(rig.proj_from_cam_translation_mm), rig.proj_from_cam_translation_mm.at<double>(0),
              rig.proj_from_cam_translation_mm.at<double>(1), rig.proj_from_cam_translation_mm.at<double>(2),
              rig.uncertainty.proj_from_cam_translation_mm.at<double>(0),
              rig.uncertainty.proj_from_cam_translation_mm.at<double>(1),
              rig.uncertainty.proj_from_cam_translation_mm.at<double>(2));
  for (std::size_t i = 0; i < run.view_names.size(); ++i) {
    std::printf("  %-24s camera %.4f px  projector %.4f px  dense %.4f px\n", run.view_names[i].c_str(),
                result.fit.camera_view_rms_px[i], result.fit.projector_view_rms_px[i], result.fit.dense_view_rms_px[i]);
  }
  std::printf("wrote %s and %s/\n", request.output.c_str(), request.report_dir.c_str());
}
}  // namespace

void add_calibrate_commands(CLI::App& app) {
  auto camera = std::make_shared<CameraOptions>();
  auto* camera_command =
      app.add_subcommand("calibrate-camera", "Calibrate a camera alone from checkerboard photographs");
  camera_command->add_option("images", camera->images, "Checkerboard images (PNG, TIFF, JPEG, ...)")->required();
  add_board_options(camera_command, camera->board);
  camera_command->add_option("-o,--output", camera->output, "Calibration file to write (OpenCV YAML)")->required();
  camera_command->add_option("--report", camera->report, "Report directory (default: OUTPUT_STEM_report)");
  camera_command->add_flag("--force", camera->force, "Replace an existing calibration file and report directory");
  camera_command->callback([camera] { run_calibrate_camera(*camera); });

  auto stereo = std::make_shared<StereoOptions>();
  auto* stereo_command = app.add_subcommand(
      "calibrate", "Calibrate camera and projector (dual photography), their stereo pose and rectification");
  stereo_command->add_option("poses", stereo->poses, "One capture directory per board pose")->required();
  add_board_options(stereo_command, stereo->board);
  stereo_command->add_option("-o,--output", stereo->output, "Rig file to write (OpenCV YAML)")->required();
  stereo_command->add_option("--report", stereo->report, "Report directory (default: OUTPUT_STEM_report)");
  stereo_command->add_flag("--force", stereo->force, "Replace an existing rig file and report directory");
  stereo_command
      ->add_option("--dense-points", stereo->dense_points,
                   "Camera-projector correspondences per pose, on the board's white squares, added to the joint "
                   "adjustment (0: corners only)")
      ->check(CLI::Range(0, 100000))
      ->capture_default_str();
  stereo_command->add_flag("--no-gating", stereo->no_gating,
                           "Keep every corner and pose at full weight (no robust gating of outlying residuals)");
  add_capture_options(stereo_command, stereo->capture);
  add_devices_option(stereo_command, stereo->devices);
  add_tile_timeout_option(stereo_command);
  stereo_command->callback([stereo] { run_calibrate(*stereo); });
}

}  // namespace rfrecon::cli
