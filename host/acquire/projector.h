// The projector seam of a capture: a display that shows one pattern image at a time, pixel for pixel
// (host/drivers/ holds the SDL2 window; sim/ the rendered rig's projector).
#pragma once

#include <string>

#include <opencv2/core.hpp>

namespace rfrecon::acquire {

class Projector {
 public:
  virtual ~Projector() = default;
  // Names the projector in messages ("SDL2 display 1").
  virtual std::string name() const = 0;
  // The resolution it shows images at, unscaled.
  virtual cv::Size size() const = 0;
  // Shows `image` (CV_8UC1 of size(), 255 = full light) pixel for pixel and returns once it was handed to the
  // display (after the vertical sync where there is one). Throws HardwareError when the display is gone.
  virtual void show(const cv::Mat& image) = 0;
};

}  // namespace rfrecon::acquire
