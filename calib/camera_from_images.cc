// The calibrate-camera loop: read, detect, report, calibrate, write.
#include "calib/camera_from_images.h"

#include <algorithm>

#include <opencv2/imgcodecs.hpp>
#include <spdlog/spdlog.h>

#include "calib/board_detection.h"
#include "calib/board_overhang.h"
#include "calib/report.h"
#include "calib/report_files.h"
#include "host/core/atomic_file.h"
#include "host/core/errors.h"
#include "host/core/image_file.h"
#include "host/core/output_path.h"
#include "host/core/progress.h"

namespace rfrecon::calib {

namespace fs = std::filesystem;

namespace {
// A view's name for reports: the file's stem, prefixed by its directory when another image has the same stem
// (e.g. pose_03/000_white.png -> "pose_03_000_white").
std::string view_name(const fs::path& file, const std::vector<fs::path>& all) {
  const auto same_stem =
      std::count_if(all.begin(), all.end(), [&](const fs::path& other) { return other.stem() == file.stem(); });
  if (same_stem <= 1) return file.stem().string();
  return file.parent_path().filename().string() + "_" + file.stem().string();
}

}  // namespace

fs::path default_report_dir(const fs::path& output) {
  return output.parent_path() / (output.stem().string() + "_report");
}

CameraImagesRun calibrate_camera_from_images(const CameraImagesRequest& request) {
  const OutputPath output{request.output, "--output", request.force};
  const OutputPath report_output{request.report_dir, "--report", request.force};
  check_output_file(output, request.images);
  check_output_directory(report_output, request.images);
  check_distinct_outputs({output, report_output});
  CameraImagesRun run;
  run.images = request.images.size();
  std::vector<BoardView> views;
  std::vector<ViewOverhang> overhangs;
  cv::Size image_size;
  StagingDirectory report(request.report_dir, true);
  Progress progress("calibrate-camera", request.images.size(), "images");
  for (const auto& file : request.images) {
    const cv::Mat image = decode_image(file, cv::IMREAD_GRAYSCALE | cv::IMREAD_ANYDEPTH);
    if (image_size.empty()) image_size = image.size();
    if (image.size() != image_size) {
      throw InputError(file.string() + ": size " + size_text(image.size()) + " differs from the first image's " +
                       size_text(image_size) + " (all views must come from one camera setting)");
    }
    auto corners = find_board_corners(image, request.board);
    const std::string name = view_name(file, request.images);
    write_image(report.path() / ("corners_" + name + ".png"), draw_corners(image, request.board, corners));
    if (corners.empty()) {
      spdlog::warn("{}: board {}x{} not found, view skipped", file.string(), request.board.cols, request.board.rows);
    } else {
      if (const auto overhang = board_overhang(image, request.board, corners); overhang.any()) {
        overhangs.push_back({file.string(), overhang});
      }
      views.push_back({name, std::move(corners)});
    }
    progress.advance();
  }
  run.calibration = keeping_report(report, [&] {
    check_board_fits(overhangs, request.board, views.size());
    auto calibration = calibrate_camera(views, request.board, image_size, request.options);
    check_intrinsics_determined("camera", calibration.camera_matrix, calibration.intrinsics_std, calibration.rms,
                                image_size, request.board, views.size());
    return calibration;
  });
  for (const auto& warning : run.calibration.warnings) spdlog::warn("calibrate-camera: {}", warning);
  write_camera_report(report.path(), run.calibration, views);
  report.commit();  // the secondary output first: a report that cannot be moved into place fails before the file
  write_camera_calibration(run.calibration, request.output);
  return run;
}

}  // namespace rfrecon::calib
