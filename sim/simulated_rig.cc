// The rendered rig behind the capture seam, with injectable display lag, late frames and repeated buffers.
#include "sim/simulated_rig.h"

#include <cmath>
#include <string>

#include "host/core/errors.h"
#include "sim/frames.h"

namespace rfrecon::sim {

class SimulatedRig::RigProjector : public acquire::Projector {
 public:
  explicit RigProjector(SimulatedRig& rig) : rig_(rig) {}
  std::string name() const override { return "simulated projector"; }
  cv::Size size() const override { return rig_.scene_.projector.size; }
  void show(const cv::Mat& image) override {
    CV_Assert(image.type() == CV_8UC1 && image.size() == size());
    const std::size_t late = rig_.faults_.late_shows.count(rig_.shows_++) != 0 ? 1 : 0;
    const std::size_t lag = static_cast<std::size_t>(rig_.faults_.display_lag_frames);
    rig_.queue_.push_back({image.clone(), rig_.grabs_ + 1 + lag + late});
  }

 private:
  SimulatedRig& rig_;
};

class SimulatedRig::RigCamera : public acquire::Camera {
 public:
  explicit RigCamera(SimulatedRig& rig) : rig_(rig) {}
  std::string name() const override { return "simulated camera"; }
  acquire::CameraFormat format() const override {
    return {rig_.scene_.camera.size, rig_.scene_.capture.bit_depth, rig_.scene_.capture.black_level};
  }
  double lock_exposure(double exposure_us) override {
    if (exposure_us > 0.0) rig_.exposure_us_ = exposure_us;
    return rig_.exposure_us_;
  }
  cv::Mat grab(std::chrono::milliseconds) override { return rig_.next_frame(); }

 private:
  SimulatedRig& rig_;
};

SimulatedRig::SimulatedRig(Scene scene, SimulatedRigFaults faults, double reference_exposure_us)
    : scene_(std::move(scene)),
      faults_(std::move(faults)),
      reference_exposure_us_(reference_exposure_us),
      exposure_us_(reference_exposure_us),
      projector_(std::make_unique<RigProjector>(*this)),
      camera_(std::make_unique<RigCamera>(*this)) {
  set_view(0);
}

SimulatedRig::~SimulatedRig() = default;

acquire::Projector& SimulatedRig::projector() { return *projector_; }
acquire::Camera& SimulatedRig::camera() { return *camera_; }

std::size_t SimulatedRig::views() const { return scene_.views.empty() ? 1 : scene_.views.size(); }

void SimulatedRig::set_view(std::size_t view) {
  if (view >= views()) {
    throw InputError("scene '" + scene_.name + "' has " + std::to_string(views()) + " view(s); there is no view " +
                     std::to_string(view + 1));
  }
  if (view == view_) return;
  T_ = render_transport(scene_.views.empty() ? scene_ : scene_for_view(scene_, view), scene_.render).T;
  view_ = view;
}

cv::Mat SimulatedRig::next_frame() {
  const std::size_t grab = grabs_++;
  while (!queue_.empty() && queue_.front().visible_at <= grabs_) {
    visible_ = queue_.front().image;
    queue_.pop_front();
  }
  if (faults_.repeat_grabs.count(grab) != 0 && !last_frame_.empty()) return last_frame_;
  if (visible_.empty()) visible_ = cv::Mat(scene_.projector.size, CV_8UC1, cv::Scalar(0));
  const double scale = exposure_us_ / reference_exposure_us_;
  cv::Mat linear = transport_image(T_, visible_, scene_.camera.size) * scale;
  CaptureSettings settings = scene_.capture;
  settings.ambient *= scale;
  last_frame_ = camera_reading(linear, settings, scene_.render.seed, grab);
  return last_frame_;
}

}  // namespace rfrecon::sim
