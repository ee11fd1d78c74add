// A rendered projector-camera rig behind the capture seam (host/acquire): the projector remembers what it shows,
// the camera renders the scene's light transport under it with the noise model, so `rfrecon capture` runs end to end
// without hardware. Faults real rigs have can be injected: display lag, a late frame, a repeated camera buffer.
#pragma once

#include <cstddef>
#include <cstdint>
#include <deque>
#include <memory>
#include <set>

#include "host/acquire/camera.h"
#include "host/acquire/projector.h"
#include "sim/render.h"
#include "sim/scene.h"

namespace rfrecon::sim {

struct SimulatedRigFaults {
  int display_lag_frames = 0;          // grabs between a show and the camera seeing it (as displays and streams add)
  std::set<std::size_t> late_shows;    // 0-based shows that appear one grab later than the lag says (a late frame)
  std::set<std::size_t> repeat_grabs;  // 0-based grabs that hand back the previous frame (a repeated buffer)
};

class SimulatedRig {
 public:
  // Renders the scene's first view (its only one for a scan scene). The camera's exposure is
  // `reference_exposure_us` at the scene's gain: other exposures scale the light linearly.
  SimulatedRig(Scene scene, SimulatedRigFaults faults = {}, double reference_exposure_us = 10000.0);
  ~SimulatedRig();
  SimulatedRig(const SimulatedRig&) = delete;
  SimulatedRig& operator=(const SimulatedRig&) = delete;

  acquire::Projector& projector();
  acquire::Camera& camera();
  // Renders view `view` of a multi-view scene (a board pose); throws InputError for one that does not exist.
  void set_view(std::size_t view);
  std::size_t views() const;

 private:
  class RigProjector;
  class RigCamera;
  friend class RigProjector;
  friend class RigCamera;

  // The camera frame of grab number grabs_: the shown pattern whose time has come, rendered.
  cv::Mat next_frame();

  Scene scene_;
  SimulatedRigFaults faults_;
  double reference_exposure_us_;
  double exposure_us_;
  TransportMatrix T_;
  std::size_t view_ = static_cast<std::size_t>(-1);  // the view T_ shows
  struct Shown {
    cv::Mat image;
    std::size_t visible_at;  // grab number from which the camera sees it
  };
  std::deque<Shown> queue_;
  cv::Mat visible_;
  cv::Mat last_frame_;
  std::size_t shows_ = 0;
  std::size_t grabs_ = 0;
  std::unique_ptr<RigProjector> projector_;
  std::unique_ptr<RigCamera> camera_;
};

}  // namespace rfrecon::sim
