// A reconstruction on the camera's pixel grid: what `rfrecon reconstruct` computes and writes, and `evaluate` reads.
#pragma once

#include <opencv2/core.hpp>

namespace rfrecon::outputs {

// All maps have the (unrectified) camera's size; values are in the camera frame, millimetres.
struct Reconstruction {
  cv::Mat depth_mm;    // CV_32F: z of the surface point seen at the pixel centre, NaN where none
  cv::Mat points_mm;   // CV_32FC3: X_cam of that point, NaN where none
  cv::Mat normals;     // CV_32FC3: unit normal facing the camera, NaN where none
  cv::Mat confidence;  // CV_32F in [0, 1]: 0 where none, higher is more trusted
  cv::Mat white;       // CV_32F: linear white frame (1 = full scale), the PLY's colour; empty: none (uncoloured)
  // One standard deviation of depth_mm (mm): the calibration's part, the observation's (the frames' noise) and their
  // root sum of squares (host/depth/depth_sigma.h). CV_32F, NaN where unknown; empty: not computed.
  cv::Mat depth_sigma_calibration_mm;
  cv::Mat depth_sigma_observation_mm;
  cv::Mat depth_sigma_mm;
};

}  // namespace rfrecon::outputs
