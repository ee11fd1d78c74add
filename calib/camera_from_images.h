// `rfrecon calibrate-camera` as a library call: a camera alone from checkerboard photographs, with its report.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "calib/camera_calibration.h"

namespace rfrecon::calib {

struct CameraImagesRequest {
  std::vector<std::filesystem::path> images;
  BoardSpec board;
  CalibrationOptions options;
  std::filesystem::path output;      // camera.yaml (OpenCV FileStorage), written atomically
  std::filesystem::path report_dir;  // corner images and the error chart, written whole
  bool force = false;                // replace an existing calibration file and report directory
};

struct CameraImagesRun {
  CameraCalibration calibration;
  std::size_t images = 0;  // given; calibration.view_names are those with the board
};

// Detects the board in each image (skipping, with a warning, images without it), calibrates, writes the report and
// then the calibration. Throws UsageError before any work for outputs that host/core/output_path.h refuses (one of
// the images, an existing one without force), InputError naming the file for an unreadable image or one of another
// size, and ProcessingError (after writing the report, which it names) when the board continues beyond the detected
// corners in any image (calib/board_overhang.h), too few views remain, the poses are degenerate or the intrinsics are
// not determined (check_intrinsics_determined).
CameraImagesRun calibrate_camera_from_images(const CameraImagesRequest& request);

// The default report directory of an output file: OUTPUT_STEM_report beside it.
std::filesystem::path default_report_dir(const std::filesystem::path& output);

}  // namespace rfrecon::calib
