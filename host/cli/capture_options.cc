// The shared capture-directory options of the command line.
#include "host/cli/capture_options.h"

#include "host/cli/size_option.h"
#include "host/transport/pipeline.h"

namespace rfrecon::cli {

void add_capture_options(CLI::App* command, CaptureOptions& options) {
  command
      ->add_option("--layout", options.layout,
                   "Capture layout: 'manifest' (DIR/manifest.json) or 'opencv-graycode' (images sorted by name: "
                   "OpenCV GrayCodePattern's sequence, then white, then black)")
      ->check(CLI::IsMember({"manifest", "opencv-graycode"}))
      ->capture_default_str();
  command->add_option("--projector", options.projector, "Projector resolution WxH (needed by opencv-graycode)");
}

capture::CaptureManifest open_capture(const std::filesystem::path& capture_dir, const CaptureOptions& options) {
  const cv::Size projector = options.projector.empty() ? cv::Size() : parse_size(options.projector, "--projector");
  return transport::open_capture(capture_dir, options.layout, projector);
}

}  // namespace rfrecon::cli
