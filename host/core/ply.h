// Binary PLY point clouds from per-pixel maps, readable by MeshLab, CloudCompare, Open3D and plyfile.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include <opencv2/core.hpp>

namespace rfrecon {

// An extra float property per vertex, taken from a CV_32F map of the points' size. MeshLab reads a property named
// `quality` as its per-vertex quality; CloudCompare imports every extra property as a scalar field.
struct PlyScalarMap {
  std::string name;
  cv::Mat values;
};

// Writes `file` atomically as `format binary_little_endian 1.0` with one vertex per pixel whose point is finite,
// in row-major pixel order: float x y z (points, CV_32FC3), float nx ny nz (normals, CV_32FC3; 0 0 0 where the
// normal is not finite), float u v (the pixel's column and row), then one float property per scalar map, in
// order (0 where not finite), then, when `colours_rgb` (CV_8UC3, R G B) is not empty, uchar red green blue (the names
// MeshLab, CloudCompare and Open3D read as the vertex colour). The file holds no NaN or infinity. `comment` becomes a
// header comment line (no newlines). Throws std::invalid_argument on maps of the wrong type or size or a bad property
// name, std::runtime_error when the file cannot be written.
void write_point_cloud_ply(const std::filesystem::path& file, const std::string& comment, const cv::Mat& points,
                           const cv::Mat& normals, const std::vector<PlyScalarMap>& scalars = {},
                           const cv::Mat& colours_rgb = cv::Mat());

}  // namespace rfrecon
