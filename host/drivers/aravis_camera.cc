// Aravis camera: GenICam features set through ArvCamera, frames from a stream of a few buffers.
#include "host/drivers/aravis_camera.h"

#include <cstring>

#include <arpa/inet.h>
#include <arv.h>
#include <spdlog/spdlog.h>

#include "host/core/errors.h"

namespace rfrecon::drivers {

namespace {

// Monochrome pixel formats from deepest to shallowest, with their significant bits.
struct MonoFormat {
  const char* name;
  int bits;
};
constexpr MonoFormat kMonoFormats[] = {{"Mono16", 16}, {"Mono12", 12}, {"Mono10", 10}, {"Mono8", 8}};

std::string take_error(GError*& error) {
  std::string message = error != nullptr ? error->message : "unknown error";
  g_clear_error(&error);
  return message;
}

class AravisCamera : public acquire::Camera {
 public:
  explicit AravisCamera(const std::string& device_id) {
    GError* error = nullptr;
    // A GigE camera named by its IPv4 address is opened directly; any other name is looked up after a fresh
    // discovery (a camera plugged in since the last look, and the interface a GigE camera's stream comes back on).
    in_addr address{};
    if (inet_pton(AF_INET, device_id.c_str(), &address) != 1) arv_update_device_list();
    camera_ = arv_camera_new(device_id.empty() ? nullptr : device_id.c_str(), &error);
    if (camera_ == nullptr) {
      std::string list;
      for (const auto& id : list_aravis_cameras()) list += "\n  " + id;
      throw HardwareError("cannot open GenICam camera '" + device_id + "' through Aravis (" + take_error(error) +
                          "); the cameras found are:" + (list.empty() ? std::string(" none") : list));
    }
    const char* model = arv_camera_get_model_name(camera_, nullptr);
    name_ =
        "GenICam camera '" + (device_id.empty() ? std::string(model != nullptr ? model : "first") : device_id) + "'";
    try {
      configure();
    } catch (...) {
      release();
      throw;
    }
  }

  ~AravisCamera() override { release(); }

  std::string name() const override { return name_; }
  acquire::CameraFormat format() const override { return format_; }

  double lock_exposure(double exposure_us) override {
    GError* error = nullptr;
    if (arv_camera_is_exposure_auto_available(camera_, nullptr)) {
      arv_camera_set_exposure_time_auto(camera_, ARV_AUTO_OFF, &error);
      if (error != nullptr) fail("refused to turn auto exposure off", error);
    }
    if (arv_camera_is_gain_auto_available(camera_, nullptr)) {
      arv_camera_set_gain_auto(camera_, ARV_AUTO_OFF, &error);
      if (error != nullptr) fail("refused to turn auto gain off", error);
    }
    if (arv_camera_is_feature_available(camera_, "BalanceWhiteAuto", nullptr)) {
      arv_camera_set_string(camera_, "BalanceWhiteAuto", "Off", &error);
      if (error != nullptr) fail("refused to turn auto white balance off", error);
    }
    if (exposure_us > 0.0) {
      arv_camera_set_exposure_time(camera_, exposure_us, &error);
      if (error != nullptr) fail("refused an exposure of " + std::to_string(exposure_us) + " us", error);
    }
    const double applied = arv_camera_get_exposure_time(camera_, &error);
    if (error != nullptr) fail("cannot read its exposure time", error);
    return applied;
  }

  cv::Mat grab(std::chrono::milliseconds timeout) override {
    for (int attempt = 0; attempt < 3; ++attempt) {
      ArvBuffer* buffer = arv_stream_timeout_pop_buffer(stream_, static_cast<guint64>(timeout.count()) * 1000);
      if (buffer == nullptr) {
        throw HardwareError(name_ + " sent no frame within " + std::to_string(timeout.count()) +
                            " ms: it was disconnected, is waiting for a trigger, or its link is too slow");
      }
      cv::Mat frame;
      if (arv_buffer_get_status(buffer) == ARV_BUFFER_STATUS_SUCCESS) frame = copy(buffer);
      arv_stream_push_buffer(stream_, buffer);
      if (!frame.empty()) return frame;
      spdlog::warn("{}: an incomplete frame (lost packets); taking the next", name_);
    }
    throw HardwareError(name_ +
                        " sent three incomplete frames in a row: check the link (GigE: packet size, jumbo "
                        "frames, a dedicated interface)");
  }

 private:
  void release() {
    if (stream_ != nullptr) {
      arv_camera_stop_acquisition(camera_, nullptr);
      g_object_unref(stream_);
      stream_ = nullptr;
    }
    g_object_unref(camera_);
  }

  // Pixel format, image size, black level and a running stream.
  void configure() {
    GError* error = nullptr;
    choose_pixel_format();
    gint x = 0, y = 0, width = 0, height = 0;
    arv_camera_get_region(camera_, &x, &y, &width, &height, &error);
    if (error != nullptr) fail("cannot read its image size", error);
    format_.size = {width, height};
    if (arv_camera_is_feature_available(camera_, "BlackLevel", nullptr)) {
      format_.black_level_dn = arv_camera_get_float(camera_, "BlackLevel", nullptr);
    }
    start_stream();
  }

  [[noreturn]] void fail(const std::string& what, GError*& error) const {
    throw HardwareError(name_ + " " + what + ": " + take_error(error));
  }

  void choose_pixel_format() {
    GError* error = nullptr;
    guint count = 0;
    const char** available = arv_camera_dup_available_pixel_formats_as_strings(camera_, &count, &error);
    if (available == nullptr) fail("cannot list its pixel formats", error);
    const MonoFormat* chosen = nullptr;
    for (const auto& format : kMonoFormats) {
      for (guint i = 0; i < count && chosen == nullptr; ++i) {
        if (std::strcmp(available[i], format.name) == 0) chosen = &format;
      }
      if (chosen != nullptr) break;
    }
    g_free(available);
    if (chosen == nullptr) {
      throw HardwareError(name_ + " offers no monochrome pixel format (Mono8 to Mono16); rfrecon reads one channel");
    }
    arv_camera_set_pixel_format_from_string(camera_, chosen->name, &error);
    if (error != nullptr) fail(std::string("refused pixel format ") + chosen->name, error);
    format_.bit_depth = chosen->bits;
  }

  void start_stream() {
    GError* error = nullptr;
    stream_ = arv_camera_create_stream(camera_, nullptr, nullptr, &error);
    if (stream_ == nullptr) fail("cannot open a stream", error);
    const guint payload = arv_camera_get_payload(camera_, &error);
    if (error != nullptr) fail("cannot tell its frame size", error);
    for (int i = 0; i < 4; ++i) arv_stream_push_buffer(stream_, arv_buffer_new(payload, nullptr));
    arv_camera_set_acquisition_mode(camera_, ARV_ACQUISITION_MODE_CONTINUOUS, &error);
    if (error != nullptr) fail("refused continuous acquisition", error);
    arv_camera_start_acquisition(camera_, &error);
    if (error != nullptr) fail("refused to start acquisition", error);
  }

  cv::Mat copy(ArvBuffer* buffer) const {
    std::size_t size = 0;
    const void* data = arv_buffer_get_data(buffer, &size);
    const int type = format_.bit_depth == 8 ? CV_8UC1 : CV_16UC1;
    const cv::Size frame_size(arv_buffer_get_image_width(buffer), arv_buffer_get_image_height(buffer));
    if (frame_size != format_.size || size < static_cast<std::size_t>(frame_size.area()) * CV_ELEM_SIZE(type)) {
      return {};
    }
    return cv::Mat(frame_size, type, const_cast<void*>(data)).clone();
  }

  ArvCamera* camera_ = nullptr;
  ArvStream* stream_ = nullptr;
  std::string name_;
  acquire::CameraFormat format_;
};

}  // namespace

std::unique_ptr<acquire::Camera> open_aravis_camera(const std::string& device_id) {
  return std::make_unique<AravisCamera>(device_id);
}

std::vector<std::string> list_aravis_cameras() {
  arv_update_device_list();
  std::vector<std::string> ids;
  for (unsigned i = 0; i < arv_get_n_devices(); ++i) ids.emplace_back(arv_get_device_id(i));
  return ids;
}

}  // namespace rfrecon::drivers
