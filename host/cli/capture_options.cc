// The shared capture-directory options of the command line.
#include "host/cli/capture_options.h"

#include "host/cli/size_option.h"

namespace rfrecon::cli {

void add_capture_options(CLI::App* command, CaptureOptions& options) {
  command
      ->add_option("--layout", options.layout,
                   "Capture layout: 'manifest' (DIR/manifest.json) or 'opencv-graycode' (images sorted by name: "
                   "OpenCV GrayCodePattern's sequence, then white, then black)")
      ->check(CLI::IsMember({"manifest", "opencv-graycode"}))
      ->capture_default_str();
  command->add_option("--projector", options.projector, "Projector resolution WxH (needed by opencv-graycode)");
  command->add_flag("--allow-outside-frames", options.allow_outside_frames,
                    "Accept manifest frames outside the capture directory (absolute paths, '..', links)");
}

transport::CaptureSource capture_source(const CaptureOptions& options) {
  return {options.layout, options.projector.empty() ? cv::Size() : parse_size(options.projector, "--projector"),
          options.allow_outside_frames ? capture::FramePaths::kAnywhere : capture::FramePaths::kInsideCapture};
}

}  // namespace rfrecon::cli
