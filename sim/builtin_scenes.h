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

// The named scene; throws InputError listing the known names when `name` is not one.
Scene builtin_scene(const std::string& name);

// A built-in scene name, else a scene file path; throws InputError when it is neither.
Scene resolve_scene(const std::string& name_or_file);

}  // namespace rfrecon::sim
