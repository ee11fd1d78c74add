// `rfrecon patterns`: writes the projector images of the capture protocol and their manifest.
#include <spdlog/spdlog.h>

#include "host/capture/pattern_files.h"
#include "host/capture/protocol.h"
#include "host/cli/commands.h"
#include "host/cli/number_checks.h"
#include "host/cli/size_option.h"

namespace rfrecon::cli {

namespace {
struct PatternsOptions {
  std::string projector;
  std::filesystem::path out;
  int dot_spacing = 8;
  bool force = false;
};

void run_patterns(const PatternsOptions& options) {
  capture::ProtocolOptions protocol;
  protocol.projector_size = parse_size(options.projector, "--projector");
  protocol.dot_spacing = options.dot_spacing;
  const auto manifest = capture::write_pattern_directory(options.out, protocol, options.force);
  spdlog::info("patterns: wrote {} images and {} to {}", manifest.frames.size(), capture::kManifestFileName,
               options.out.string());
}
}  // namespace

void add_patterns_command(CLI::App& app) {
  auto options = std::make_shared<PatternsOptions>();
  auto* command = app.add_subcommand("patterns", "Write the projector pattern sequence (Gray code, dot grid)");
  command->add_option("--projector", options->projector, "Projector resolution WxH, e.g. 1024x768")->required();
  command->add_option("-o,--output", options->out, "Output directory (created)")->required();
  command->add_option("--dot-spacing", options->dot_spacing, "Dot grid spacing s (s x s frames); 0 = Gray code only")
      ->check(zero_or_range(2, capture::kMaxDotSpacing, "Gray code only"))
      ->capture_default_str();
  command->add_flag("--force", options->force, "Replace an existing non-empty output directory");
  command->callback([options] { run_patterns(*options); });
}

}  // namespace rfrecon::cli
