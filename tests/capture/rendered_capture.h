// Test helper: a capture of the small test rig (tests/sim/test_scenes.h: a tilted matte plane, 80x60 camera and
// projector) rendered into a directory, with the capture settings a test changes.
#pragma once

#include <filesystem>
#include <functional>

#include "host/capture/manifest.h"
#include "sim/frames.h"
#include "sim/render.h"
#include "tests/sim/test_scenes.h"

namespace rfrecon::testing {

// Renders the plane (dot spacing 4, ambient 0.01, 10-bit; then `adjust`) into `dir` and reads its manifest back.
inline capture::CaptureManifest render_capture(const std::filesystem::path& dir,
                                               const std::function<void(sim::Scene&)>& adjust) {
  sim::Scene scene =
      sim::testing::make_scene(sim::testing::small_rig({sim::testing::tilted_plane(sim::testing::kLambert)}));
  scene.capture.dot_spacing = 4;
  scene.capture.ambient = 0.01;
  adjust(scene);
  const sim::Transport transport = sim::render_transport(scene);
  sim::write_capture(transport.T, scene.capture, scene.camera.size, scene.projector.size, 1, 2, dir);
  return capture::read_manifest(dir);
}

}  // namespace rfrecon::testing
