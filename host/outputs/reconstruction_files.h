// The reconstruction output directory (docs/formats.md): float maps, the point cloud, previews and a summary.
#pragma once

#include <filesystem>

#include <nlohmann/json.hpp>

#include "host/outputs/reconstruction.h"

namespace rfrecon::outputs {

// The maps read_reconstruction reads back, in its directory.
inline constexpr const char* kReconstructionMaps[] = {"depth.tiff", "normals.tiff", "confidence.tiff"};

// Writes `out_dir` through a StagingDirectory (it appears whole or not at all): depth.tiff, normals.tiff,
// confidence.tiff, points.ply (pixels with finite points; x y z nx ny nz quality = confidence), the previews
// depth.png, normals.png and confidence.png, and summary.json (`summary`, pretty-printed). An existing out_dir that
// is not an empty directory is an InputError unless `force`, and is then replaced once the new one is complete.
// Throws std::invalid_argument when the maps do not have the types and common size of Reconstruction.
void write_reconstruction(const Reconstruction& reconstruction, const nlohmann::json& summary,
                          const std::filesystem::path& out_dir, bool force);

// Reads depth_mm, normals and confidence back from a directory written by write_reconstruction (points_mm is left
// empty: the files do not record the pixel of each PLY vertex). Throws InputError naming the file when one is
// missing, unreadable, of the wrong type or of another size than depth.tiff.
Reconstruction read_reconstruction(const std::filesystem::path& dir);

// The 8-bit BGR previews written by write_reconstruction. Depth: COLORMAP_TURBO from the 1st (blue) to the 99th
// (red) percentile of the finite depths; normals: RGB = 255 (n + 1) / 2; confidence: grey 255 * confidence. Pixels
// without depth are black in all three.
cv::Mat depth_preview(const cv::Mat& depth_mm);
cv::Mat normals_preview(const cv::Mat& normals, const cv::Mat& depth_mm);
cv::Mat confidence_preview(const cv::Mat& confidence, const cv::Mat& depth_mm);

}  // namespace rfrecon::outputs
