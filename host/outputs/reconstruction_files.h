// The reconstruction output directory (docs/formats.md): float maps, the point cloud, previews and a summary.
#pragma once

#include <filesystem>
#include <utility>

#include <nlohmann/json.hpp>

#include "host/outputs/reconstruction.h"

namespace rfrecon::outputs {

// The maps read_reconstruction reads back, in its directory.
inline constexpr const char* kReconstructionMaps[] = {"depth.tiff", "points.tiff", "normals.tiff", "confidence.tiff"};

// Writes `out_dir` through a StagingDirectory (it appears whole or not at all): depth.tiff, points.tiff,
// normals.tiff (the 3-channel TIFFs with x in the file's first sample, as any TIFF reader sees it), confidence.tiff,
// points.ply (pixels with finite points; x y z nx ny nz u v quality = confidence, and red green blue from the white
// frame when reconstruction.white is not empty), the previews depth.png, normals.png and confidence.png, each with its
// legend, and summary.json (`summary`, pretty-printed). An existing out_dir that is not an empty directory is an
// InputError unless `force` (the commands refuse it earlier, before any work, as a UsageError: exit 2), and is then
// replaced once the new one is complete. Throws std::invalid_argument when the
// maps do not have the types and common size of Reconstruction.
void write_reconstruction(const Reconstruction& reconstruction, const nlohmann::json& summary,
                          const std::filesystem::path& out_dir, bool force);

// Reads depth_mm, points_mm, normals and confidence back from a directory written by write_reconstruction (white is
// left empty). Throws InputError naming the file when one is missing, unreadable, of the wrong type or of another
// size than depth.tiff (a directory of an rfrecon before points.tiff, whose normals.tiff had z first, has none).
Reconstruction read_reconstruction(const std::filesystem::path& dir);

// The 8-bit BGR previews on the camera grid, without their legends. Depth: COLORMAP_TURBO from the 1st (blue) to the
// 99th (red) percentile of the finite depths (depth_preview_range); normals: RGB = 255 (n + 1) / 2; confidence: grey
// 255 * confidence. Pixels without depth are black in all three.
cv::Mat depth_preview(const cv::Mat& depth_mm);
cv::Mat normals_preview(const cv::Mat& normals, const cv::Mat& depth_mm);
cv::Mat confidence_preview(const cv::Mat& confidence, const cv::Mat& depth_mm);

// The depths at the two ends of depth_preview's colour scale; NaN, NaN without any finite depth.
std::pair<double, double> depth_preview_range(const cv::Mat& depth_mm);

// The PLY's vertex colour of a linear white frame: grey, R = G = B = 255 sRGB(clamp(white, 0, 1)) rounded, sRGB's
// transfer function (IEC 61966-2-1), so that a brighter white pixel is a brighter vertex. CV_8UC3 in R G B order.
cv::Mat white_colours_rgb(const cv::Mat& white);

}  // namespace rfrecon::outputs
