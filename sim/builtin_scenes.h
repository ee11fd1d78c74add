// The built-in named scenes of the synthetic rig (docs/sim.md describes each).
#pragma once

#include <string>
#include <vector>

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

}  // namespace rfrecon::sim
