// The lens distortion models a calibration may estimate, as OpenCV calibration flags and coefficient lists.
#pragma once

#include <string>
#include <vector>

namespace rfrecon::calib {

enum class DistortionModel {
  radial,    // k1, k2
  standard,  // k1, k2, p1, p2 (Bouguet's toolbox default: k3 = 0)
  full,      // k1, k2, p1, p2, k3 (wide-angle lenses)
  rational,  // k1, k2, p1, p2, k3, k4, k5, k6 (OpenCV's rational model; strong distortion, many poses)
};

// "radial", "standard", "full" or "rational"; throws InputError naming `option` for any other text.
DistortionModel parse_distortion_model(const std::string& text, const std::string& option);
const char* distortion_model_name(DistortionModel model);

// The cv::calibrateCamera / cv::stereoCalibrate flags that estimate exactly this model's coefficients.
int distortion_flags(DistortionModel model);

// The number of coefficients of the model's OpenCV vector (5, or 8 for the rational model) and the indices in it of
// the coefficients the model estimates (the others are held at 0).
int distortion_vector_size(DistortionModel model);
std::vector<int> estimated_distortion_indices(DistortionModel model);

}  // namespace rfrecon::calib
