// The built-in projector-camera rigs of the synthetic scenes (docs/sim.md): a scene names one with its `rig` key, or
// `rfrecon simulate --rig NAME` puts one under any scene.
#pragma once

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace rfrecon::sim {

// The rig of every built-in scene unless told otherwise.
inline constexpr const char* kDefaultRig = "projector-above";

struct BuiltinRigInfo {
  std::string name;
  std::string description;
};

std::vector<BuiltinRigInfo> builtin_rigs();

// {"camera": ..., "projector": ...} of the named rig, in the scene format; throws InputError listing the known names.
nlohmann::json builtin_rig(const std::string& name);

// The scene JSON with its devices replaced by the named rig (its `camera` and `projector` keys removed).
nlohmann::json with_rig(nlohmann::json scene, const std::string& rig);

}  // namespace rfrecon::sim
