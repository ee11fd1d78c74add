// `rfrecon patterns`: writes the projector images of the capture protocol and their manifest.
#include <cstdio>

#include <opencv2/imgcodecs.hpp>
#include <spdlog/spdlog.h>

#include "host/capture/manifest.h"
#include "host/cli/commands.h"
#include "host/cli/size_option.h"
#include "host/common/atomic_file.h"

namespace rfrecon::cli {

namespace {
struct PatternsOptions {
  std::string projector;
  std::filesystem::path out;
  int dot_spacing = 8;
  bool force = false;
};

// "007_gray_col_b2_inv.png": the sequence number keeps name order equal to projection order.
std::string pattern_file_name(std::size_t index, const capture::Pattern& pattern) {
  std::string name = capture::to_string(pattern.kind);
  if (pattern.kind == capture::PatternKind::kGrayColumn || pattern.kind == capture::PatternKind::kGrayRow) {
    name += "_b" + std::to_string(pattern.bit) + (pattern.inverse ? "_inv" : "");
  } else if (pattern.kind == capture::PatternKind::kDot) {
    name += "_" + std::to_string(pattern.dot_offset_x) + "_" + std::to_string(pattern.dot_offset_y);
  }
  char number[24];
  std::snprintf(number, sizeof(number), "%03zu_", index);
  return number + name + ".png";
}

void run_patterns(const PatternsOptions& options) {
  capture::ProtocolOptions protocol;
  protocol.projector_size = parse_size(options.projector, "--projector");
  protocol.dot_spacing = options.dot_spacing;
  const auto sequence = capture::make_protocol(protocol);
  StagingDirectory staging(options.out, options.force);
  capture::CaptureManifest manifest;
  manifest.projector_size = protocol.projector_size;
  manifest.dot_spacing = protocol.dot_spacing;
  for (std::size_t i = 0; i < sequence.size(); ++i) {
    const std::string file = pattern_file_name(i, sequence[i]);
    const cv::Mat image = capture::render_pattern(sequence[i], protocol.projector_size, protocol.dot_spacing);
    if (!cv::imwrite((staging.path() / file).string(), image)) {
      throw std::runtime_error("cannot write " + (staging.path() / file).string());
    }
    manifest.frames.push_back({sequence[i], file});
  }
  capture::write_manifest(manifest, staging.path());
  staging.commit();
  spdlog::info("patterns: wrote {} images and {} to {}", sequence.size(), capture::kManifestFileName,
               options.out.string());
}
}  // namespace

void add_patterns_command(CLI::App& app) {
  auto options = std::make_shared<PatternsOptions>();
  auto* command = app.add_subcommand("patterns", "Write the projector pattern sequence (Gray code, dot grid)");
  command->add_option("--projector", options->projector, "Projector resolution WxH, e.g. 1024x768")->required();
  command->add_option("--out", options->out, "Output directory (created)")->required();
  command->add_option("--dot-spacing", options->dot_spacing, "Dot grid spacing s (s x s frames); 0 = Gray code only")
      ->capture_default_str();
  command->add_flag("--force", options->force, "Replace an existing non-empty output directory");
  command->callback([options] { run_patterns(*options); });
}

}  // namespace rfrecon::cli
