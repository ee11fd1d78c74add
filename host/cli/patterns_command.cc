// `rfrecon patterns`: writes the projector images of the capture protocol and their manifest.
#include <spdlog/spdlog.h>

#include "host/capture/pattern_files.h"
#include "host/capture/protocol.h"
#include "host/cli/commands.h"
#include "host/cli/protocol_option.h"
#include "host/cli/size_option.h"

namespace rfrecon::cli {

namespace {
struct PatternsOptions {
  std::string projector;
  std::filesystem::path out;
  std::shared_ptr<capture::ProtocolOptions> protocol = std::make_shared<capture::ProtocolOptions>();
  bool force = false;
};

void run_patterns(const PatternsOptions& options) {
  capture::ProtocolOptions protocol = *options.protocol;
  protocol.projector_size = parse_size(options.projector, "--projector");
  const auto manifest = capture::write_pattern_directory(options.out, protocol, options.force);
  spdlog::info("patterns: wrote {} images and {} to {}", manifest.frames.size(), capture::kManifestFileName,
               options.out.string());
}
}  // namespace

void add_patterns_command(CLI::App& app) {
  auto options = std::make_shared<PatternsOptions>();
  auto* command = app.add_subcommand("patterns", "Write the projector pattern sequence of a pattern family");
  command->add_option("--projector", options->projector, "Projector resolution WxH, e.g. 1024x768")->required();
  command->add_option("-o,--output", options->out, "Output directory (created)")->required();
  add_protocol_options(*command, options->protocol);
  command->add_flag("--force", options->force, "Replace an existing non-empty output directory");
  command->callback([options] { run_patterns(*options); });
}

}  // namespace rfrecon::cli
