// One checkerboard pose of a projector-camera calibration: the camera image, the dual image T^T 1 seen from the
// projector, and the board corners found in each (paper section 3, after Sen et al.'s dual photography).
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <opencv2/core.hpp>

#include "calib/rig.h"
#include "host/cl/device_context.h"
#include "host/cl/program_cache.h"
#include "host/sched/report.h"
#include "host/transport/transport_types.h"

namespace rfrecon::calibration {

struct PoseObservation {
  std::string name;                            // the pose directory
  cv::Mat camera_image;                        // CV_32F linear white frame (camera size)
  cv::Mat dual_image;                          // CV_32F T^T 1 (projector size), holes filled for detection
  std::vector<cv::Point2f> camera_corners;     // empty when the board was not found
  std::vector<cv::Point2f> projector_corners;  // empty when the board was not found; same order as camera_corners
  std::string problem;                         // why the pose is unusable; empty when both corner sets were found
  std::vector<sched::RunReport> schedule;      // the transport and dual stages per device (host/sched)
  bool usable() const { return problem.empty(); }
};

// Where the compressed T of a pose comes from: the capture layout, thresholds and the device to run on.
struct PoseSource {
  std::string layout;       // "" (manifest.json) or "opencv-graycode"
  cv::Size projector_size;  // needed for opencv-graycode
  transport::Thresholds thresholds;
};

// Builds T for the capture in `pose_dir` on `devices` (host/sched), forms T^T 1, and finds the board in the white frame
// and in the dual image. The projector corners are put in the camera corners' order by mapping two camera corners
// through the decoded correspondences (the detector may number a board from either end). Input errors (missing frames,
// bad manifest) throw InputError; a board that is not found is reported in `problem`.
PoseObservation observe_pose(const std::filesystem::path& pose_dir, const PoseSource& source,
                             const calib::BoardSpec& board, std::vector<cl::DeviceContext>& devices,
                             cl::ProgramCache& programs);

// Reverses `projector_corners` when that matches the camera corners mapped through `correspondence` (camera pixel
// -> projector x, y; CV_32FC2, NaN where unknown) better than the given order. Returns false when neither end of the
// camera board maps to a known correspondence.
bool align_corner_order(const std::vector<cv::Point2f>& camera_corners, const cv::Mat& correspondence,
                        std::vector<cv::Point2f>& projector_corners);

}  // namespace rfrecon::calibration
