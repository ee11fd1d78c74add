// Opening the named rig (hardware or simulated) and running the capture on it.
#include "host/pipeline/capture_rig.h"

#include "host/core/errors.h"
#include "host/core/output_path.h"
#include "host/drivers/open_devices.h"
#include "sim/builtin_scenes.h"

namespace rfrecon::pipeline {

namespace {

// A camera and projector pair: opened drivers, or a simulated rig.
struct OpenRig {
  std::unique_ptr<sim::SimulatedRig> simulated;
  std::unique_ptr<acquire::Camera> camera;
  std::unique_ptr<acquire::Projector> projector;
  acquire::Camera& camera_ref() const { return simulated ? simulated->camera() : *camera; }
  acquire::Projector& projector_ref() const { return simulated ? simulated->projector() : *projector; }
};

OpenRig open_rig(const CaptureRequest& request) {
  OpenRig rig;
  const std::string sim_prefix = "sim:";
  if (request.camera.rfind(sim_prefix, 0) == 0) {
    sim::SceneChanges changes;
    changes.seed = request.seed;
    rig.simulated = std::make_unique<sim::SimulatedRig>(
        sim::resolve_scene(request.camera.substr(sim_prefix.size()), changes), request.faults);
    return rig;
  }
  if (request.seed) throw UsageError("--seed applies to a simulated camera (--camera sim:SCENE) only");
  if (request.projector.empty()) throw UsageError("--projector is required with a real camera (display:N)");
  rig.camera = drivers::open_camera(request.camera);
  rig.projector = drivers::open_projector(request.projector);
  return rig;
}

}  // namespace

std::vector<acquire::CaptureRunReport> capture(const CaptureRequest& request) {
  check_output_directory({request.output, "--output", request.force}, {});
  OpenRig rig = open_rig(request);
  auto& camera = rig.camera_ref();
  auto& projector = rig.projector_ref();
  if (request.poses == 0 && !(rig.simulated && rig.simulated->views() > 1)) {
    return {acquire::capture_scan(projector, camera, request.run, request.output, request.force)};
  }
  int poses = request.poses;
  std::function<void(int)> before_pose = request.before_pose ? request.before_pose : [](int) {};
  if (rig.simulated) {
    if (poses == 0) poses = static_cast<int>(rig.simulated->views());
    before_pose = [&](int pose) { rig.simulated->set_view(static_cast<std::size_t>(pose)); };
  }
  return acquire::capture_poses(projector, camera, request.run, poses, before_pose, request.output, request.force);
}

int measure_latency(const CaptureRequest& request) {
  OpenRig rig = open_rig(request);
  return acquire::measure_latency(rig.projector_ref(), rig.camera_ref(), request.run);
}

}  // namespace rfrecon::pipeline
