// The account of lost pixels, from the counts of triangulation and segmentation.
#include "host/depth/pixel_losses.h"

#include <spdlog/fmt/fmt.h>

namespace rfrecon::depth {

std::string where_pixels_went(const nlohmann::json& summary, const CameraGridTriangulation& triangulation,
                              const DepthOptions& options, const std::string& rig_name) {
  std::string why = std::to_string(triangulation.off_epipolar) + " off their epipolar line by more than " +
                    fmt::format("{:g}", options.rectification.epipolar_tolerance_px) + " px (--epipolar-tolerance; " +
                    "is " + rig_name + " this capture's calibration?), " +
                    std::to_string(triangulation.boundary_pixels) + " on object boundaries, " +
                    std::to_string(triangulation.edge_pixels) + " on albedo or shadow edges (--edge-relative)";
  if (summary.contains("segmentation")) {
    const auto& segmentation = summary["segmentation"];
    why += ", " + std::to_string(segmentation["usable_pixels"].get<int>()) +
           " usable rectified samples for the integration (others lack primal or dual signal, or saturate: "
           "--saturation), in runs ended by " +
           std::to_string(segmentation["jumps"].get<int>()) + " depth jumps (--jump) and " +
           std::to_string(segmentation["creases"].get<int>()) + " creases (--crease)";
  }
  return why;
}

}  // namespace rfrecon::depth
