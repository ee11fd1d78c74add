// SDL2 projector window: one streaming texture of the display's size, copied 1:1 and presented with vsync.
#include "host/drivers/sdl_projector.h"

#include <algorithm>
#include <string>
#include <vector>

#include <SDL2/SDL.h>
#include <opencv2/imgproc.hpp>

#include "host/core/errors.h"

namespace rfrecon::drivers {

namespace {

// SDL's video subsystem, started once for the process without SDL's own signal handlers (rfrecon's remove a
// capture's temporaries on Ctrl-C).
void start_video() {
  SDL_SetHint(SDL_HINT_NO_SIGNAL_HANDLERS, "1");
  SDL_SetHint(SDL_HINT_VIDEO_MINIMIZE_ON_FOCUS_LOSS, "0");
  if (SDL_WasInit(SDL_INIT_VIDEO) == 0 && SDL_InitSubSystem(SDL_INIT_VIDEO) != 0) {
    throw HardwareError(
        std::string("no display to show patterns on: SDL could not start video (") + SDL_GetError() +
        "); run on the machine the projector is attached to, with DISPLAY (X11) or WAYLAND_DISPLAY set");
  }
}

std::string describe_display(int index) {
  SDL_Rect bounds{};
  SDL_GetDisplayBounds(index, &bounds);
  SDL_DisplayMode mode{};
  SDL_GetCurrentDisplayMode(index, &mode);
  const char* name = SDL_GetDisplayName(index);
  return "display " + std::to_string(index) + " '" + (name != nullptr ? name : "?") + "' " + std::to_string(bounds.w) +
         "x" + std::to_string(bounds.h) + " at (" + std::to_string(bounds.x) + ", " + std::to_string(bounds.y) + "), " +
         (mode.refresh_rate > 0 ? std::to_string(mode.refresh_rate) : "?") + " Hz";
}

class SdlProjector : public acquire::Projector {
 public:
  explicit SdlProjector(int display_index) : index_(display_index) {
    start_video();
    const int displays = SDL_GetNumVideoDisplays();
    if (display_index < 0 || display_index >= displays) {
      std::string list;
      for (int i = 0; i < displays; ++i) list += "\n  " + describe_display(i);
      throw HardwareError("there is no display " + std::to_string(display_index) + "; the displays are:" + list);
    }
    SDL_Rect bounds{};
    SDL_GetDisplayBounds(display_index, &bounds);
    size_ = {bounds.w, bounds.h};
    window_ = SDL_CreateWindow("rfrecon capture", bounds.x, bounds.y, bounds.w, bounds.h,
                               SDL_WINDOW_FULLSCREEN_DESKTOP | SDL_WINDOW_BORDERLESS);
    if (window_ != nullptr) renderer_ = SDL_CreateRenderer(window_, -1, SDL_RENDERER_PRESENTVSYNC);
    if (renderer_ != nullptr) {
      texture_ = SDL_CreateTexture(renderer_, SDL_PIXELFORMAT_RGB24, SDL_TEXTUREACCESS_STREAMING, bounds.w, bounds.h);
    }
    if (texture_ == nullptr) {
      const std::string error = SDL_GetError();
      close();
      throw HardwareError("cannot open a full-screen window on " + describe_display(display_index) + ": " + error);
    }
    SDL_ShowCursor(SDL_DISABLE);
    int width = 0;
    int height = 0;
    SDL_GetWindowSize(window_, &width, &height);
    if (width != size_.width || height != size_.height) {
      const std::string what = describe_display(display_index);
      close();
      throw HardwareError("the window on " + what + " is " + std::to_string(width) + "x" + std::to_string(height) +
                          ", not the display's size: the window manager refused full screen");
    }
  }
  ~SdlProjector() override { close(); }

  std::string name() const override { return "SDL2 display " + std::to_string(index_); }
  cv::Size size() const override { return size_; }

  void show(const cv::Mat& image) override {
    CV_Assert(image.type() == CV_8UC1 && image.size() == size_);
    cv::cvtColor(image, rgb_, cv::COLOR_GRAY2RGB);
    SDL_PumpEvents();
    if (SDL_UpdateTexture(texture_, nullptr, rgb_.data, static_cast<int>(rgb_.step)) != 0 ||
        SDL_RenderCopy(renderer_, texture_, nullptr, nullptr) != 0) {
      throw HardwareError(name() + " stopped showing patterns: " + SDL_GetError());
    }
    SDL_RenderPresent(renderer_);
  }

 private:
  void close() {
    if (texture_ != nullptr) SDL_DestroyTexture(texture_);
    if (renderer_ != nullptr) SDL_DestroyRenderer(renderer_);
    if (window_ != nullptr) SDL_DestroyWindow(window_);
    texture_ = nullptr;
    renderer_ = nullptr;
    window_ = nullptr;
  }

  int index_;
  cv::Size size_;
  SDL_Window* window_ = nullptr;
  SDL_Renderer* renderer_ = nullptr;
  SDL_Texture* texture_ = nullptr;
  cv::Mat rgb_;
};

}  // namespace

std::unique_ptr<acquire::Projector> open_sdl_projector(int display_index) {
  return std::make_unique<SdlProjector>(display_index);
}

std::vector<std::string> list_displays() {
  start_video();
  const int displays = SDL_GetNumVideoDisplays();
  std::vector<std::string> lines;
  lines.reserve(static_cast<std::size_t>(std::max(displays, 0)));
  for (int i = 0; i < displays; ++i) lines.push_back(describe_display(i));
  return lines;
}

}  // namespace rfrecon::drivers
