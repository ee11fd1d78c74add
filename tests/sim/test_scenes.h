// Small scenes for the synthetic-rig tests: an 80x60 camera and projector (f = 100 px) 150 mm apart, looking at
// a point 600 mm ahead, so whole renders take milliseconds.
#pragma once

#include <vector>

#include <nlohmann/json.hpp>

#include "sim/scene.h"

namespace rfrecon::sim::testing {

// A matte material for the scenes below.
inline const nlohmann::json kLambert{{"brdf", "lambert"}, {"diffuse", 0.6}};

// `objects` is a vector, not a json: `json x = {one}` is an array under g++ but a copy of `one` under clang.
inline nlohmann::json small_rig(const std::vector<nlohmann::json>& objects) {
  return {{"name", "test"},
          {"camera", {{"size", {80, 60}}, {"focal", {100.0, 100.0}}}},
          {"projector",
           {{"size", {80, 60}},
            {"focal", {100.0, 100.0}},
            {"pose", {{"position", {150.0, 0.0, 0.0}}, {"look_at", {0.0, 0.0, 600.0}}}}}},
          {"radiometry", {{"intensity", 1.0e6}}},
          {"objects", objects}};
}

inline nlohmann::json tilted_plane(const nlohmann::json& material) {
  return {{"name", "plane"},
          {"shape", "plane"},
          {"pose", {{"position", {0.0, 0.0, 600.0}}, {"rotation_deg", {10.0, 25.0, 0.0}}}},
          {"material", material},
          {"tangent", {1.0, 2.0, 0.0}}};
}

inline Scene make_scene(const nlohmann::json& json) { return scene_from_json(json, "test scene", {}); }

}  // namespace rfrecon::sim::testing
