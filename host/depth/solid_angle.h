// Solid angle seen by each pixel of a pinhole device with OpenCV lens distortion: the radiometric normalisation of
// the primal and dual images before the reciprocity ODE (docs/method.md).
#pragma once

#include <opencv2/core.hpp>

namespace rfrecon::depth {

// CV_32F map of `size`: Omega(x, y) = cos^3(theta) * |det d(x_n, y_n) / d(x, y)| (steradians per pixel), where
// (x_n, y_n) are the undistorted normalised coordinates of the pixel and theta the angle of its ray to the optical
// axis. Without distortion this is cos^3(theta) / (f_x f_y).
cv::Mat pixel_solid_angles(const cv::Mat& camera_matrix, const cv::Mat& dist_coeffs, cv::Size size);

}  // namespace rfrecon::depth
