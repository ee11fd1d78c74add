// The residual field of a calibration: every corner's residual (projected - detected) drawn as an arrow from where
// it was detected, over the device's image, all poses in one image, at a scale written on the image. A lens model
// that does not fit shows as arrows that turn with the position; a bad corner as one long arrow.
#pragma once

#include <string>
#include <vector>

#include <opencv2/core.hpp>

namespace rfrecon::calib {

// The arrows over `background` (8-bit grey or colour, the device's size; it sets the image's size), dimmed; one
// colour per pose, corners dropped by gating (`dropped`, per view and corner, may be empty) in red with a circle.
// Arrows are the residuals times a scale from the 1-2-5 series that draws the 95th percentile residual about 40 px
// long; the scale and a bar of a round residual length are written on the image.
cv::Mat draw_residual_field(const cv::Mat& background, const std::vector<std::string>& view_names,
                            const std::vector<std::vector<cv::Point2f>>& detected_px,
                            const std::vector<std::vector<cv::Point2d>>& residuals_px,
                            const std::vector<std::vector<unsigned char>>& dropped, const std::string& title);

}  // namespace rfrecon::calib
