// Ground-truth outputs of the synthetic rig: the true calibration and the per-pixel maps, as files.
#pragma once

#include <filesystem>

#include "calib/rig.h"
#include "sim/render.h"

namespace rfrecon::sim {

// The scene's true rig (rms 0, no per-view errors; board from the first checkerboard object, if any).
calib::StereoRig true_rig(const Scene& scene);

// Writes depth.tiff, normals.tiff, visibility.png, shadow.png, correspondences.tiff (x, y, 0: 3 channels, as
// cv::imwrite has no 2-channel images), object_id.png and points.ply into `dir` (which must exist).
void write_ground_truth(const GroundTruth& truth, const std::filesystem::path& dir);

// Binary little-endian PLY of the visible surface points (x, y, z, nx, ny, nz as float; camera frame, mm).
void write_points_ply(const GroundTruth& truth, const std::filesystem::path& file);

}  // namespace rfrecon::sim
