// `rfrecon simulate` as a library call (the noise seed is scene.render.seed): renders a scene and writes the capture
// directory (or one per view), the ground truth and the resolved scene into an output directory that appears whole or
// not at all.
#pragma once

#include <filesystem>
#include <vector>

#include "sim/scene.h"

namespace rfrecon::sim {

struct SimulateOptions {
  int threads = 0;                            // 0 = hardware concurrency
  bool force = false;                         // replace a non-empty existing output directory
  std::vector<std::filesystem::path> inputs;  // files the scene came from: the output may not hold them
};

// Layout (docs/sim.md): single-view scenes: OUT/capture/, OUT/truth/{depth.tiff, normals.tiff, visibility.png,
// shadow.png, correspondences.tiff, object_id.png, points.ply, rig.yaml}, OUT/scene.json. Multi-view scenes:
// OUT/capture/pose_NN/, OUT/truth/pose_NN/ (maps as above), OUT/truth/rig.yaml, OUT/truth/board_poses.json,
// OUT/scene.json. Throws InputError when OUT exists and is not empty (without force).
void simulate(const Scene& scene, const std::filesystem::path& out_dir, const SimulateOptions& options);

}  // namespace rfrecon::sim
