// Distortion models as OpenCV flags.
#include "calib/distortion_model.h"

#include <opencv2/calib3d.hpp>

#include "host/core/errors.h"

namespace rfrecon::calib {

namespace {
struct ModelInfo {
  DistortionModel model;
  const char* name;
  int flags;
  std::vector<int> estimated;
};

const std::vector<ModelInfo>& models() {
  static const std::vector<ModelInfo> kModels = {
      {DistortionModel::radial, "radial", cv::CALIB_ZERO_TANGENT_DIST | cv::CALIB_FIX_K3, {0, 1}},
      {DistortionModel::standard, "standard", cv::CALIB_FIX_K3, {0, 1, 2, 3}},
      {DistortionModel::full, "full", 0, {0, 1, 2, 3, 4}},
      {DistortionModel::rational, "rational", cv::CALIB_RATIONAL_MODEL, {0, 1, 2, 3, 4, 5, 6, 7}},
  };
  return kModels;
}

const ModelInfo& info(DistortionModel model) {
  for (const auto& entry : models()) {
    if (entry.model == model) return entry;
  }
  throw std::logic_error("unknown distortion model");
}
}  // namespace

DistortionModel parse_distortion_model(const std::string& text, const std::string& option) {
  for (const auto& entry : models()) {
    if (text == entry.name) return entry.model;
  }
  throw InputError(option + " " + text + ": expected radial, standard, full or rational");
}

const char* distortion_model_name(DistortionModel model) { return info(model).name; }

int distortion_flags(DistortionModel model) { return info(model).flags; }

int distortion_vector_size(DistortionModel model) { return model == DistortionModel::rational ? 8 : 5; }

std::vector<int> estimated_distortion_indices(DistortionModel model) { return info(model).estimated; }

}  // namespace rfrecon::calib
