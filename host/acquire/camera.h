// The camera seam of a capture: what `rfrecon capture` needs from a camera, so that a vendor SDK plugs in by
// implementing it (host/drivers/ holds Aravis and OpenCV VideoCapture; sim/ a rendered camera).
#pragma once

#include <chrono>
#include <string>

#include <opencv2/core.hpp>

namespace rfrecon::acquire {

// What a camera's frames are: the manifest's camera fields.
struct CameraFormat {
  cv::Size size;              // pixels
  int bit_depth = 8;          // significant bits per sample: 8, 10, 12 or 16
  double black_level_dn = 0;  // reading with no light, digital numbers
};

class Camera {
 public:
  virtual ~Camera() = default;
  // Names the camera in messages ("Aravis camera 'Fake_1'").
  virtual std::string name() const = 0;
  virtual CameraFormat format() const = 0;
  // Sets the exposure time with every automatic control the camera has (exposure, gain, white balance) off, and
  // returns the exposure it applied (cameras round it), in microseconds, or 0 when it cannot tell. 0 asks for the
  // exposure as it is. Throws HardwareError when it cannot.
  virtual double lock_exposure(double exposure_us) = 0;
  // The next frame of the camera's stream: one channel, CV_8U for 8 bits, else CV_16U holding 0..2^bit_depth-1, of
  // format().size. A stream may hand back a frame exposed before the call (a buffered one): the capture run discards
  // the measured latency's frames after each change. Throws HardwareError when no frame comes within `timeout`.
  virtual cv::Mat grab(std::chrono::milliseconds timeout) = 0;
};

}  // namespace rfrecon::acquire
