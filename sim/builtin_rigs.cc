// Built-in rigs as scene JSON devices, so that they go through the same validation as scene files.
#include "sim/builtin_rigs.h"

#include "host/core/errors.h"
#include "host/core/message_text.h"

namespace rfrecon::sim {

using nlohmann::json;

namespace {

// 640x480 camera and projector side by side, the projector 150 mm to the right and toed in toward the scene 560-600
// mm ahead; mild lens distortion, an off-centre projector principal point.
json side_by_side() {
  return {{"camera",
           {{"size", {640, 480}},
            {"focal", {820.0, 818.0}},
            {"principal_point", {322.0, 236.5}},
            {"distortion", {-0.08, 0.05, 0.0005, -0.0003, 0.0}}}},
          {"projector",
           {{"size", {640, 480}},
            {"focal", {880.0, 880.0}},
            {"principal_point", {319.5, 290.0}},
            {"distortion", {0.03, 0.0, 0.0, 0.0, 0.0}},
            {"pose", {{"position", {150.0, 0.0, 0.0}}, {"look_at", {0.0, 30.0, 560.0}}}}}}};
}

// A 5:4 camera (640x512, a 1280x1024 sensor binned 2x2) under a 4:3 projector (640x480) with its lens offset: the
// principal point 96 rows from the top edge, so the image is thrown downward. The projector sits 170 mm above the
// camera and 20 mm to its right, tilted down a little.
json projector_above() {
  return {{"camera",
           {{"size", {640, 512}},
            {"focal", {800.0, 799.0}},
            {"principal_point", {325.0, 252.0}},
            {"distortion", {-0.08, 0.05, 0.0005, -0.0003, 0.0}}}},
          {"projector",
           {{"size", {640, 480}},
            {"focal", {860.0, 860.0}},
            {"principal_point", {330.0, 96.0}},
            {"distortion", {0.03, 0.0, 0.0, 0.0, 0.0}},
            {"pose", {{"position", {20.0, -170.0, 0.0}}, {"look_at", {0.0, -104.0, 600.0}}}}}}};
}

// A 640x480 camera and a 512x384 projector 280 mm to its left and 60 mm above, toed in strongly: a diagonal
// baseline, the projector's pixels 1.2 times the camera's at the scene.
json wide_baseline() {
  return {{"camera",
           {{"size", {640, 480}},
            {"focal", {820.0, 820.0}},
            {"principal_point", {318.0, 242.0}},
            {"distortion", {-0.06, 0.03, 0.0, 0.0, 0.0}}}},
          {"projector",
           {{"size", {512, 384}},
            {"focal", {700.0, 700.0}},
            {"principal_point", {270.0, 200.0}},
            {"distortion", {0.02, 0.0, 0.0, 0.0, 0.0}},
            {"pose", {{"position", {-280.0, -60.0, 20.0}}, {"look_at", {0.0, 0.0, 600.0}}}}}}};
}

struct BuiltinRig {
  const char* name;
  const char* description;
  json (*make)();
};

const BuiltinRig kRigs[] = {
    {"projector-above",
     "640x512 camera, 640x480 projector 170 mm above it with its lens offset (principal point near the top edge)",
     projector_above},
    {"side-by-side", "640x480 camera and projector, the projector 150 mm to the right", side_by_side},
    {"wide-baseline", "640x480 camera, 512x384 projector 280 mm to the left and 60 mm above, toed in", wide_baseline},
};

}  // namespace

std::vector<BuiltinRigInfo> builtin_rigs() {
  std::vector<BuiltinRigInfo> out;
  for (const auto& rig : kRigs) out.push_back({rig.name, rig.description});
  return out;
}

json builtin_rig(const std::string& name) {
  std::string known;
  for (const auto& rig : kRigs) {
    if (name == rig.name) return rig.make();
    known += known.empty() ? rig.name : std::string(", ") + rig.name;
  }
  throw InputError("unknown rig '" + excerpt(name) + "' (built-in rigs: " + known + ")");
}

json with_rig(json scene, const std::string& rig) {
  scene.erase("camera");
  scene.erase("projector");
  scene["rig"] = rig;
  return scene;
}

}  // namespace rfrecon::sim
