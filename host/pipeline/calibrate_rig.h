// `rfrecon calibrate` as a library call: camera and projector from one capture per board pose (dual photography),
// their stereo pose and rectification, with the visual report.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "calib/stereo_calibration.h"
#include "host/capture/frame_source.h"
#include "host/capture/manifest.h"
#include "host/core/atomic_file.h"
#include "host/sched/report.h"
#include "host/transport/capture_views.h"

namespace rfrecon::pipeline {

struct RigCalibrationRequest {
  std::vector<std::filesystem::path> pose_dirs;  // one capture directory per board pose
  transport::CaptureSource source;
  calib::BoardSpec board;
  calib::CalibrationOptions options;
  std::filesystem::path output;      // rig.yaml, written atomically
  std::filesystem::path report_dir;  // camera and dual images with corners, error chart, schedule.json; written whole
  bool force = false;                // replace an existing rig file and report directory
};

struct RigCalibrationRun {
  calib::StereoCalibration calibration;
  std::vector<std::string> view_names;     // the poses used, in order of the per-view errors
  std::size_t poses = 0;                   // given
  std::vector<sched::RunReport> schedule;  // per stage, summed over the poses
};

// A pose's name in the report and the per-view errors: its capture directory's name ("pose_03", also for "pose_03/").
std::string pose_name(const std::filesystem::path& pose_dir);

// One board pose's capture from any source: its name in the report and the per-view errors, its frames (a capture
// directory, a camera, memory; the source's name stands for the pose in messages) and their manifest.
struct PoseCapture {
  std::string name;
  capture::FrameSource frames;
  capture::CaptureManifest manifest;
};

// The calibration of calibrate_rig from captures of any source, with the same checks and errors; the report's files
// go into `report` when it is given (the caller commits it), and no rig file is written.
RigCalibrationRun calibrate_poses(const std::vector<PoseCapture>& poses, const calib::BoardSpec& board,
                                  const calib::CalibrationOptions& options, StagingDirectory* report,
                                  std::vector<cl::DeviceContext>& devices, cl::ProgramCache& programs);

// For each pose: T and T^T 1 on `devices`, corners in both images (a pose without the board is skipped with a
// warning); then calibrates, writes the report and then rig.yaml. Throws UsageError before any work for outputs that
// host/core/output_path.h refuses (one of the captures' files, an existing one without force), InputError for a bad
// capture or mixed sizes (naming the pose), ProcessingError (after writing the report, which it names) when the board
// continues beyond the detected corners in any pose (calib/board_overhang.h), when no pose or too few remain, the
// poses are degenerate or the intrinsics are not determined (calib/camera_calibration.h): no rig.yaml is written then.
RigCalibrationRun calibrate_rig(const RigCalibrationRequest& request, std::vector<cl::DeviceContext>& devices,
                                cl::ProgramCache& programs);

}  // namespace rfrecon::pipeline
