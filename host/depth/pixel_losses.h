// Where the pixels with a correspondence went, each loss with the option that sets it: the text of the depth stage's
// warning when fewer than half are reconstructed and of its error when none is.
#pragma once

#include <string>

#include <nlohmann/json.hpp>

#include "host/depth/depth_method.h"

namespace rfrecon::depth {

// From the triangulation's counts and, where a method wrote it, summary["segmentation"].
std::string where_pixels_went(const nlohmann::json& summary, const CameraGridTriangulation& triangulation,
                              const DepthOptions& options, const std::string& rig_name);

}  // namespace rfrecon::depth
