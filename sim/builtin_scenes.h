// The built-in named scenes of the synthetic rig (docs/sim.md describes each).
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <opencv2/core.hpp>

#include "sim/scene.h"

namespace rfrecon::sim {

struct BuiltinSceneInfo {
  std::string name;
  std::string description;
};

std::vector<BuiltinSceneInfo> builtin_scenes();

// The named scene, on the named built-in rig (sim/builtin_rigs.h) when `rig` is not empty; throws InputError listing
// the known names when `name` or `rig` is not one.
Scene builtin_scene(const std::string& name, const std::string& rig = "");

// A built-in scene name, else a scene file path, on the named rig when `rig` is not empty; throws InputError when it
// is neither.
Scene resolve_scene(const std::string& name_or_file, const std::string& rig = "");

// What `rfrecon simulate` changes in the scene it resolves (docs/cli.md); each one left empty keeps the scene's.
struct SceneChanges {
  std::string rig;                          // a built-in rig replacing the camera and projector
  cv::Size camera_size;                     // the camera's resolution, its field of view kept
  cv::Size projector_size;                  // the same for the projector
  std::optional<int> supersample;           // rays per pixel side
  std::optional<int> interreflection;       // one-bounce rays per sample, 0 = off (render.interreflection_samples)
  std::string family;                       // a pattern family; other than graycode, the dot spacing is 0 unless given
  std::map<std::string, int> parameters{};  // the family's parameters (replacing the scene's when family is given)
  std::optional<int> dot_spacing;           // 0 (no dot grid) or at least 2: InputError for 1
  std::optional<unsigned long long> seed;   // the frames' noise seed
  std::string format;                       // the frame files' format, "tiff" or "png" (capture.format)
};

// resolve_scene(name_or_file, changes.rig) with the other changes made.
Scene resolve_scene(const std::string& name_or_file, const SceneChanges& changes);

// The files the scene named by `name_or_file` comes from (the output of simulate may not hold them): the scene file,
// none for a built-in name.
std::vector<std::filesystem::path> scene_files(const std::string& name_or_file);

}  // namespace rfrecon::sim
