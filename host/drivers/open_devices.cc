// Camera and projector specs of the command line to drivers.
#include "host/drivers/open_devices.h"

#include <algorithm>
#include <cctype>

#include "host/core/errors.h"
#include "host/drivers/aravis_camera.h"
#include "host/drivers/sdl_projector.h"
#include "host/drivers/video_camera.h"

namespace rfrecon::drivers {

namespace {
// The part of `spec` after "kind:" when it starts so.
bool take_kind(const std::string& spec, const std::string& kind, std::string& rest) {
  if (spec.rfind(kind + ":", 0) != 0) return false;
  rest = spec.substr(kind.size() + 1);
  return true;
}
}  // namespace

std::unique_ptr<acquire::Camera> open_camera(const std::string& spec) {
  std::string rest;
  if (spec == "aravis") return open_aravis_camera("");
  if (take_kind(spec, "aravis", rest)) return open_aravis_camera(rest);
  if (take_kind(spec, "v4l2", rest)) return open_v4l2_camera(rest);
  if (take_kind(spec, "gst", rest)) return open_gstreamer_camera(rest);
  throw UsageError("--camera '" + spec + "': expected aravis, aravis:ID, v4l2:DEVICE, gst:PIPELINE or sim:SCENE");
}

std::unique_ptr<acquire::Projector> open_projector(const std::string& spec) {
  std::string rest;
  if (take_kind(spec, "display", rest) && !rest.empty() && rest.size() < 4 &&
      std::all_of(rest.begin(), rest.end(), [](unsigned char c) { return std::isdigit(c) != 0; })) {
    return open_sdl_projector(std::stoi(rest));
  }
  throw UsageError("--projector '" + spec + "': expected display:N (SDL2's display N; --list-displays lists them)");
}

}  // namespace rfrecon::drivers
