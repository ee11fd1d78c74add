// What the synthetic rig knows as truth about a scene: its true rig and its objects as the truth files describe them.
#pragma once

#include <vector>

#include "calib/rig.h"
#include "host/truth/ground_truth.h"
#include "sim/scene.h"

namespace rfrecon::sim {

// The scene's true rig (rms 0, no per-view errors; board from the first checkerboard object, if any).
calib::StereoRig true_rig(const Scene& scene);

// The scene's objects, labelled 1, 2, ... in order, with their characteristic sizes (characteristic_size_mm).
std::vector<truth::TruthObject> truth_objects(const Scene& scene);

}  // namespace rfrecon::sim
