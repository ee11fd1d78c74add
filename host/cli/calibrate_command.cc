// `rfrecon calibrate` (camera + projector through dual images, stereo pose, rectification) and
// `rfrecon calibrate-camera` (a camera alone from checkerboard photographs).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iostream>

#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>
#include <spdlog/spdlog.h>

#include "calib/board_detection.h"
#include "calib/camera_calibration.h"
#include "calib/stereo_calibration.h"
#include "host/calibration/pose_observation.h"
#include "host/calibration/report.h"
#include "host/cl/device_selection.h"
#include "host/cli/capture_options.h"
#include "host/cli/commands.h"
#include "host/cli/size_option.h"
#include "host/common/atomic_file.h"
#include "host/common/errors.h"
#include "host/common/progress.h"
#include "host/sched/report.h"

namespace rfrecon::cli {

namespace fs = std::filesystem;

namespace {
struct BoardOptions {
  std::string board;  // COLSxROWS inner corners
  double square_mm = 0.0;
  bool full_distortion = false;
};

calib::BoardSpec board_spec(const BoardOptions& options) {
  const cv::Size size = parse_size(options.board, "--board");
  if (size.width < 2 || size.height < 2) throw InputError("--board needs at least 2x2 inner corners");
  if (size.width == size.height) {
    throw InputError("--board " + options.board +
                     ": use a board whose inner corner counts differ (e.g. 9x6), so its orientation is unambiguous");
  }
  return {size.width, size.height, options.square_mm};
}

void add_board_options(CLI::App* command, BoardOptions& options) {
  command->add_option("--board", options.board, "Inner corners of the checkerboard, COLSxROWS (e.g. 9x6)")->required();
  command->add_option("--square", options.square_mm, "Side of one square, in mm")
      ->required()
      ->check(CLI::PositiveNumber);
  command->add_flag("--full-distortion", options.full_distortion, "Also estimate k3 (wide-angle lenses)");
}

// Runs a calibration step; when it cannot process the views, the report (corner images) is still written, so the
// user can see which boards were found, and the error names it. No calibration file is written in that case.
template <typename Step>
auto keeping_report(StagingDirectory& report, Step&& step) {
  try {
    return step();
  } catch (const ProcessingError& error) {
    report.commit();
    throw ProcessingError(std::string(error.what()) + "; corner images in " + report.target().string());
  }
}

fs::path default_report_dir(const fs::path& output) {
  return output.parent_path() / (output.stem().string() + "_report");
}

void print_intrinsics(const char* device, const cv::Mat& matrix, const cv::Mat& dist) {
  std::printf("%-10s fx %.2f  fy %.2f  cx %.2f  cy %.2f  k1 %.4f  k2 %.4f px\n", device, matrix.at<double>(0, 0),
              matrix.at<double>(1, 1), matrix.at<double>(0, 2), matrix.at<double>(1, 2), dist.at<double>(0),
              dist.at<double>(1));
}

// ---- calibrate-camera -------------------------------------------------------------------------------------------
// A view's name for reports: the file's stem, prefixed by its directory when another image has the same stem
// (e.g. pose_03/000_white.png -> "pose_03_000_white").
std::string view_name(const std::string& file, const std::vector<std::string>& all) {
  const fs::path path(file);
  const auto same_stem = std::count_if(all.begin(), all.end(),
                                       [&](const std::string& other) { return fs::path(other).stem() == path.stem(); });
  if (same_stem <= 1) return path.stem().string();
  return path.parent_path().filename().string() + "_" + path.stem().string();
}

struct CameraOptions {
  std::vector<std::string> images;
  BoardOptions board;
  std::string output;
  std::string report;
};

void run_calibrate_camera(const CameraOptions& options) {
  const auto board = board_spec(options.board);
  std::vector<calib::BoardView> views;
  cv::Size image_size;
  StagingDirectory report(options.report.empty() ? default_report_dir(options.output) : fs::path(options.report), true);
  Progress progress("calibrate-camera", options.images.size(), "images");
  for (const auto& file : options.images) {
    const cv::Mat image = cv::imread(file, cv::IMREAD_GRAYSCALE | cv::IMREAD_ANYDEPTH);
    if (image.empty()) throw InputError("cannot read image " + file + " (missing, unreadable or not an image)");
    if (image_size.empty()) image_size = image.size();
    if (image.size() != image_size) {
      throw InputError(file + ": size " + std::to_string(image.cols) + "x" + std::to_string(image.rows) +
                       " differs from the first image's " + std::to_string(image_size.width) + "x" +
                       std::to_string(image_size.height) + " (all views must come from one camera setting)");
    }
    auto corners = calib::find_board_corners(image, board);
    const std::string name = view_name(file, options.images);
    calibration::write_image(report.path() / ("corners_" + name + ".png"),
                             calibration::draw_corners(image, board, corners));
    if (corners.empty()) {
      spdlog::warn("{}: board {} not found, view skipped", file, options.board.board);
    } else {
      views.push_back({name, std::move(corners)});
    }
    progress.advance();
  }
  calib::CalibrationOptions calibration_options;
  calibration_options.full_distortion = options.board.full_distortion;
  const auto result =
      keeping_report(report, [&] { return calib::calibrate_camera(views, board, image_size, calibration_options); });
  calibration::write_image(report.path() / "errors.png",
                           calibration::draw_error_chart(result.view_names, {"camera"}, {result.per_view_errors}));
  calib::write_camera_calibration(result, options.output);
  report.commit();
  std::printf("%zu of %zu views used; reprojection RMS %.4f px\n", views.size(), options.images.size(), result.rms);
  print_intrinsics("camera", result.camera_matrix, result.dist_coeffs);
  for (std::size_t i = 0; i < result.view_names.size(); ++i) {
    std::printf("  %-24s %.4f px\n", result.view_names[i].c_str(), result.per_view_errors[i]);
  }
  std::printf("wrote %s and %s/\n", options.output.c_str(), report.target().c_str());
}

// ---- calibrate --------------------------------------------------------------------------------------------------
// Adds each stage report of one pose to the stage of the same name in `total`.
void merge_stages(std::vector<sched::RunReport>& total, const std::vector<sched::RunReport>& pose) {
  for (const auto& stage : pose) {
    const auto same = std::find_if(total.begin(), total.end(),
                                   [&](const sched::RunReport& existing) { return existing.stage == stage.stage; });
    if (same == total.end()) {
      total.push_back(stage);
    } else {
      same->merge(stage);
    }
  }
}

struct StereoOptions {
  std::vector<std::string> poses;
  BoardOptions board;
  std::string output;
  std::string report;
  CaptureOptions capture;
  std::string devices;
};

void run_calibrate(const StereoOptions& options) {
  const auto board = board_spec(options.board);
  calibration::PoseSource source;
  source.layout = options.capture.layout;
  if (!options.capture.projector.empty()) source.projector_size = parse_size(options.capture.projector, "--projector");
  auto devices = cl::open_devices(options.devices);
  cl::ProgramCache programs;
  std::vector<sched::RunReport> schedule;  // per stage, summed over the poses
  StagingDirectory report(options.report.empty() ? default_report_dir(options.output) : fs::path(options.report), true);

  std::vector<calib::StereoView> views;
  cv::Size camera_size;
  cv::Size projector_size;
  Progress progress("calibrate", options.poses.size(), "poses");
  for (const auto& pose_dir : options.poses) {
    const auto pose = calibration::observe_pose(pose_dir, source, board, devices, programs);
    merge_stages(schedule, pose.schedule);
    if (camera_size.empty()) {
      camera_size = pose.camera_image.size();
      projector_size = pose.dual_image.size();
    }
    if (pose.camera_image.size() != camera_size || pose.dual_image.size() != projector_size) {
      throw InputError(pose_dir + ": camera or projector size differs from the first pose's (mixed captures)");
    }
    calibration::write_image(report.path() / ("camera_" + pose.name + ".png"),
                             calibration::draw_corners(pose.camera_image, board, pose.camera_corners));
    calibration::write_image(report.path() / ("dual_" + pose.name + ".png"),
                             calibration::draw_corners(pose.dual_image, board, pose.projector_corners));
    if (pose.usable()) {
      views.push_back({pose.name, pose.camera_corners, pose.projector_corners});
    } else {
      spdlog::warn("{}: {}; pose skipped", pose_dir, pose.problem);
    }
    progress.advance();
  }
  calib::CalibrationOptions calibration_options;
  calibration_options.full_distortion = options.board.full_distortion;
  const auto result = keeping_report(report, [&] {
    if (views.empty()) {
      throw ProcessingError("the board (" + options.board.board + ") was found in none of the " +
                            std::to_string(options.poses.size()) + " poses");
    }
    return calib::calibrate_stereo(views, board, camera_size, projector_size, calibration_options);
  });
  std::vector<std::string> names;
  for (const auto& view : views) names.push_back(view.name);
  calibration::write_image(
      report.path() / "errors.png",
      calibration::draw_error_chart(names, {"camera", "projector"},
                                    {result.per_view_camera_errors, result.per_view_projector_errors}));
  write_file_atomically(report.path() / "schedule.json", nlohmann::json(schedule).dump(2) + "\n");
  calib::write_rig(result.rig, options.output);
  report.commit();
  sched::log_reports(schedule);

  std::printf("%zu of %zu poses used; stereo reprojection RMS %.4f px\n", views.size(), options.poses.size(),
              result.rig.rms);
  print_intrinsics("camera", result.rig.camera_matrix, result.rig.dist_coeffs);
  print_intrinsics("projector", result.rig.projector_matrix, result.rig.projector_dist_coeffs);
  std::printf("baseline   %.3f mm  (T = [%.3f %.3f %.3f])\n", cv::norm(result.rig.T), result.rig.T.at<double>(0),
              result.rig.T.at<double>(1), result.rig.T.at<double>(2));
  for (std::size_t i = 0; i < views.size(); ++i) {
    std::printf("  %-24s camera %.4f px  projector %.4f px\n", names[i].c_str(), result.per_view_camera_errors[i],
                result.per_view_projector_errors[i]);
  }
  std::printf("wrote %s and %s/\n", options.output.c_str(), report.target().c_str());
}
}  // namespace

void add_calibrate_commands(CLI::App& app) {
  auto camera = std::make_shared<CameraOptions>();
  auto* camera_command =
      app.add_subcommand("calibrate-camera", "Calibrate a camera alone from checkerboard photographs");
  camera_command->add_option("images", camera->images, "Checkerboard images (PNG, TIFF, JPEG, ...)")
      ->required()
      ->check(CLI::ExistingFile);
  add_board_options(camera_command, camera->board);
  camera_command->add_option("-o,--output", camera->output, "Calibration file to write (OpenCV YAML)")->required();
  camera_command->add_option("--report", camera->report, "Report directory (default: OUTPUT_STEM_report)");
  camera_command->callback([camera] { run_calibrate_camera(*camera); });

  auto stereo = std::make_shared<StereoOptions>();
  auto* stereo_command = app.add_subcommand(
      "calibrate", "Calibrate camera and projector (dual photography), their stereo pose and rectification");
  stereo_command->add_option("poses", stereo->poses, "One capture directory per board pose")
      ->required()
      ->check(CLI::ExistingDirectory);
  add_board_options(stereo_command, stereo->board);
  stereo_command->add_option("-o,--output", stereo->output, "Rig file to write (OpenCV YAML)")->required();
  stereo_command->add_option("--report", stereo->report, "Report directory (default: OUTPUT_STEM_report)");
  add_capture_options(stereo_command, stereo->capture);
  add_devices_option(stereo_command, stereo->devices);
  stereo_command->callback([stereo] { run_calibrate(*stereo); });
}

}  // namespace rfrecon::cli
