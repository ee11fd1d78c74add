// The ground-truth file format of a rendered view (docs/formats.md): per-pixel maps as images, the visible points as
// PLY and the scene's objects as objects.json. The synthetic rig writes it; evaluation reads it.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include <opencv2/core.hpp>

namespace rfrecon::truth {

// Per camera pixel, for the ray through the pixel centre. Camera frame, millimetres.
struct TruthMaps {
  cv::Mat depth_mm;        // CV_32F: z of the surface point, NaN where the ray hits nothing
  cv::Mat points_mm;       // CV_32FC3: X_cam of the surface point, NaN where none
  cv::Mat normals;         // CV_32FC3: unit surface normal facing the camera, NaN where none
  cv::Mat visible;         // CV_8U: 255 where the ray hits a surface
  cv::Mat shadow;          // CV_8U: 255 where visible but unlit (occluded toward the projector, facing away from it,
                           // or outside its image)
  cv::Mat correspondence;  // CV_32FC2: projector pixel (x, y) of the surface point (may lie outside the projector
                           // image), NaN where none or behind the projector
  cv::Mat object_id;       // CV_16U: the label of the object seen (TruthObject::label), 0 where none
};

// One object of the scene, as evaluation needs it.
struct TruthObject {
  int label = 0;  // its value in object_id: 1 + index in the scene's objects
  std::string name;
  std::string shape;      // "box", "sphere", "cylinder", "plane", "mesh"
  double size_mm = 0.0;   // characteristic size; 0 when it has none (an infinite plane)
  std::string size_rule;  // how size_mm was measured, e.g. "longest edge"
};

// Writes depth.tiff, normals.tiff, visibility.png, shadow.png, correspondences.tiff (x, y, 0: 3 channels, as
// cv::imwrite has no 2-channel images), object_id.png, points.ply and objects.json into `dir` (which must exist).
void write_truth(const std::filesystem::path& dir, const TruthMaps& maps, const std::vector<TruthObject>& objects);

// Binary little-endian PLY of the finite points (x, y, z, nx, ny, nz as float; camera frame, mm).
void write_truth_points(const std::filesystem::path& file, const TruthMaps& maps);

// What evaluation reads of a truth folder: depth_mm, normals and object_id (the other maps left empty) and the
// objects.
struct TruthView {
  std::filesystem::path dir;  // the truth folder
  TruthMaps maps;
  std::vector<TruthObject> objects;
};

// Reads the truth folder `dir`, or DIR/truth when `dir` is the output directory of a single-view rendering. Throws
// InputError naming the file when one is missing, malformed or of another size than depth.tiff, and naming the
// folders when `dir` holds one truth folder per view (a multi-view rendering).
TruthView read_truth(const std::filesystem::path& dir);

}  // namespace rfrecon::truth
