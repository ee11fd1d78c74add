// The calibrate loop over poses: transport views, corners, stereo calibration, report, rig file.
#include "host/pipeline/calibrate_rig.h"

#include <algorithm>

#include <nlohmann/json.hpp>
#include <spdlog/spdlog.h>

#include "calib/board_detection.h"
#include "calib/board_overhang.h"
#include "calib/pose_observation.h"
#include "calib/report.h"
#include "calib/report_files.h"
#include "host/core/atomic_file.h"
#include "host/core/errors.h"
#include "host/core/image_file.h"
#include "host/core/output_path.h"
#include "host/core/progress.h"
#include "host/transport/compute_transport.h"

namespace rfrecon::pipeline {

namespace fs = std::filesystem;

namespace {
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

// The brightest of each pose's 8-bit detection image at every pixel: the backdrop of the residual fields.
void add_to_background(cv::Mat& background, const cv::Mat& image) {
  const cv::Mat levels = calib::to_detection_image(image);
  if (background.empty()) {
    background = levels.clone();
  } else {
    cv::max(background, levels, background);
  }
}

}  // namespace

std::string pose_name(const fs::path& pose_dir) {
  return pose_dir.filename().empty() ? pose_dir.parent_path().filename().string() : pose_dir.filename().string();
}

RigCalibrationRun calibrate_poses(const std::vector<PoseCapture>& poses, const calib::BoardSpec& board,
                                  const calib::CalibrationOptions& options, StagingDirectory* report,
                                  std::vector<cl::DeviceContext>& devices, cl::ProgramCache& programs) {
  RigCalibrationRun run;
  run.poses = poses.size();
  std::vector<calib::StereoView> views;
  std::vector<calib::ViewOverhang> overhangs;
  std::size_t boards_found = 0;  // poses with the board in the camera image
  std::string first_problem;     // of the first pose skipped, for the message when none is usable
  cv::Size camera_size;
  cv::Size projector_size;
  cv::Mat camera_background;
  cv::Mat projector_background;
  Progress progress("calibrate", poses.size(), "poses");
  for (const auto& capture : poses) {
    const std::string where = capture.frames.name();
    const auto captured = transport::view_capture(capture.frames, capture.manifest, devices, programs);
    merge_stages(run.schedule, captured.schedule);
    for (const auto& finding : captured.checks.findings) spdlog::warn("{}: {}", where, finding.message);
    const auto pose = calib::observe_board(capture.name, captured.camera_image, captured.dual_image,
                                           captured.dual_reached, captured.correspondence, board);
    if (camera_size.empty()) {
      camera_size = pose.camera_image.size();
      projector_size = pose.dual_image.size();
    }
    if (pose.camera_image.size() != camera_size || pose.dual_image.size() != projector_size) {
      throw InputError(where + ": camera or projector size differs from the first pose's (mixed captures)");
    }
    if (report != nullptr) {
      write_image(report->path() / ("camera_" + pose.name + ".png"),
                  calib::draw_corners(pose.camera_image, board, pose.camera_corners));
      write_image(report->path() / ("dual_" + pose.name + ".png"),
                  calib::draw_corners(pose.dual_image, board, pose.projector_corners));
    }
    if (!pose.camera_corners.empty()) ++boards_found;
    if (pose.camera_overhang.any()) overhangs.push_back({where, pose.camera_overhang});
    if (pose.usable()) {
      add_to_background(camera_background, pose.camera_image);
      add_to_background(projector_background, pose.dual_image);
      views.push_back({pose.name, pose.camera_corners, pose.projector_corners,
                       calib::sample_dense_correspondences(pose.camera_image, captured.correspondence,
                                                           pose.camera_corners, options.dense_points)});
      run.view_names.push_back(pose.name);
    } else {
      spdlog::warn("{}: {}; pose skipped", where, pose.problem);
      if (first_problem.empty()) first_problem = where + ": " + pose.problem;
    }
    progress.advance();
  }
  const auto calibrate = [&] {
    calib::check_board_fits(overhangs, board, boards_found);
    if (views.empty()) {
      throw ProcessingError("none of the " + std::to_string(poses.size()) + " poses is usable with " +
                            calib::board_options_text(board) + " (" + first_problem + "): " + calib::kBoardAdvice);
    }
    return calib::calibrate_stereo(views, board, camera_size, projector_size, options);
  };
  run.calibration = report != nullptr ? calib::keeping_report(*report, calibrate) : calibrate();
  for (const auto& warning : run.calibration.warnings) spdlog::warn("calibrate: {}", warning);
  for (const auto& decision : run.calibration.gating) spdlog::warn("calibrate: gating: {}", decision.describe());
  if (report != nullptr) {
    calib::write_stereo_report(report->path(), run.calibration, views, camera_background, projector_background);
    write_file_atomically(report->path() / "schedule.json", nlohmann::json(run.schedule).dump(2) + "\n");
  }
  return run;
}

RigCalibrationRun calibrate_rig(const RigCalibrationRequest& request, std::vector<cl::DeviceContext>& devices,
                                cl::ProgramCache& programs) {
  std::vector<fs::path> inputs;
  std::vector<PoseCapture> poses;
  for (const auto& pose_dir : request.pose_dirs) {
    auto manifest = transport::open_capture(pose_dir, request.source.layout, request.source.projector_size,
                                            request.source.frame_paths, request.source.bit_depth);
    const auto files = capture::capture_files(pose_dir, manifest);
    inputs.insert(inputs.end(), files.begin(), files.end());
    poses.push_back({pose_name(pose_dir), pose_dir, std::move(manifest)});
  }
  const OutputPath output{request.output, "--output", request.force};
  const OutputPath report_output{request.report_dir, "--report", request.force};
  check_output_file(output, inputs);
  check_output_directory(report_output, inputs);
  check_distinct_outputs({output, report_output});
  StagingDirectory report(request.report_dir, true);
  auto run = calibrate_poses(poses, request.board, request.options, &report, devices, programs);
  report.commit();  // the secondary output first: a report that cannot be moved into place fails before rig.yaml
  calib::write_rig(run.calibration.rig, request.output);
  return run;
}

}  // namespace rfrecon::pipeline
