// The shared capture-directory options of the command line.
#include "host/cli/capture_options.h"

#include <cmath>

#include <spdlog/fmt/fmt.h>
#include <spdlog/spdlog.h>

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
  command
      ->add_option("--bit-depth", options.bit_depth,
                   "Camera bits per sample with --layout opencv-graycode: 8 (8-bit files), or 10, 12, 16 (16-bit "
                   "files holding 0..2^bits-1); default: the files' own")
      ->check(CLI::IsMember({8, 10, 12, 16}));
  command->add_flag("--allow-outside-frames", options.allow_outside_frames,
                    "Accept manifest frames outside the capture directory (absolute paths, '..', links)");
}

transport::CaptureSource capture_source(const CaptureOptions& options) {
  return {options.layout, options.projector.empty() ? cv::Size() : parse_size(options.projector, "--projector"),
          options.allow_outside_frames ? capture::FramePaths::kAnywhere : capture::FramePaths::kInsideCapture,
          options.bit_depth};
}

void log_check_findings(const capture::CaptureCheckResult& result, const std::string& capture_dir) {
  std::string measures =
      fmt::format("capture checks: {} sampled pixels, {} lit", result.sampled_pixels, result.lit_pixels);
  for (const auto& measure : capture::measures_of(result)) {
    if (!std::isfinite(measure.value)) continue;
    measures +=
        fmt::format("; {} {:.4g}{}{}", measure.name, measure.value, *measure.unit != 0 ? " " : "", measure.unit);
  }
  spdlog::info("{}", measures);
  for (const auto& finding : result.findings) spdlog::warn("{}: {}", capture_dir, finding.message);
}

}  // namespace rfrecon::cli
