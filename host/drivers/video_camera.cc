// VideoCapture cameras: frames to one channel at the camera's bit depth, exposure locked through V4L2's controls.
#include "host/drivers/video_camera.h"

#include <algorithm>
#include <cctype>
#include <memory>

#include <opencv2/imgproc.hpp>
#include <opencv2/videoio.hpp>
#include <spdlog/spdlog.h>

#include "host/core/errors.h"

namespace rfrecon::drivers {

namespace {

class VideoCamera : public acquire::Camera {
 public:
  VideoCamera(std::unique_ptr<cv::VideoCapture> capture, std::string name, bool v4l2)
      : capture_(std::move(capture)), name_(std::move(name)), v4l2_(v4l2) {
    first_ = grab(std::chrono::milliseconds(0));
    format_ = {first_.size(), first_.depth() == CV_8U ? 8 : 16, 0.0};
  }

  std::string name() const override { return name_; }
  acquire::CameraFormat format() const override { return format_; }

  double lock_exposure(double exposure_us) override {
    if (!v4l2_) {
      if (exposure_us > 0.0) {
        spdlog::warn("{}: a GStreamer pipeline's exposure is set in its source element; --exposures is ignored", name_);
      }
      return exposure_us;
    }
    // V4L2: auto exposure 1 = manual; exposure in units of 100 us (V4L2_CID_EXPOSURE_ABSOLUTE).
    capture_->set(cv::CAP_PROP_AUTO_EXPOSURE, 1);
    capture_->set(cv::CAP_PROP_AUTO_WB, 0);
    capture_->set(cv::CAP_PROP_AUTOFOCUS, 0);
    if (exposure_us > 0.0 && !capture_->set(cv::CAP_PROP_EXPOSURE, exposure_us / 100.0)) {
      throw HardwareError(name_ + " refused an exposure of " + std::to_string(exposure_us) + " us");
    }
    return capture_->get(cv::CAP_PROP_EXPOSURE) * 100.0;
  }

  cv::Mat grab(std::chrono::milliseconds) override {
    cv::Mat frame;
    if (!first_.empty()) {
      std::swap(frame, first_);
      return frame;
    }
    if (!capture_->read(frame) || frame.empty()) {
      throw HardwareError(name_ + " sent no frame: it was unplugged, or another program holds it");
    }
    if (frame.channels() == 3) cv::cvtColor(frame, frame, cv::COLOR_BGR2GRAY);
    if (frame.channels() == 4) cv::cvtColor(frame, frame, cv::COLOR_BGRA2GRAY);
    if (frame.depth() != CV_8U && frame.depth() != CV_16U) {
      throw HardwareError(name_ + " sends frames of OpenCV depth " + std::to_string(frame.depth()) +
                          "; rfrecon needs 8- or 16-bit samples");
    }
    return frame;
  }

 private:
  std::unique_ptr<cv::VideoCapture> capture_;
  std::string name_;
  bool v4l2_;
  cv::Mat first_;
  acquire::CameraFormat format_;
};

}  // namespace

std::unique_ptr<acquire::Camera> open_v4l2_camera(const std::string& device) {
  auto capture = std::make_unique<cv::VideoCapture>();
  const bool index = !device.empty() &&
                     std::all_of(device.begin(), device.end(), [](unsigned char c) { return std::isdigit(c) != 0; });
  if (index) {
    capture->open(std::stoi(device), cv::CAP_V4L2);
  } else {
    capture->open(device, cv::CAP_V4L2);
  }
  if (!capture->isOpened()) {
    throw HardwareError("cannot open V4L2 camera '" + device +
                        "': no such device, or another program holds it (v4l2-ctl --list-devices lists them)");
  }
  capture->set(cv::CAP_PROP_BUFFERSIZE, 1);
  return std::make_unique<VideoCamera>(std::move(capture), "V4L2 camera '" + device + "'", true);
}

std::unique_ptr<acquire::Camera> open_gstreamer_camera(const std::string& pipeline) {
  auto capture = std::make_unique<cv::VideoCapture>(pipeline, cv::CAP_GSTREAMER);
  if (!capture->isOpened()) {
    throw HardwareError("cannot start GStreamer pipeline '" + pipeline +
                        "': check it with gst-launch-1.0 (its last element must be appsink)");
  }
  return std::make_unique<VideoCamera>(std::move(capture), "GStreamer camera", false);
}

}  // namespace rfrecon::drivers
