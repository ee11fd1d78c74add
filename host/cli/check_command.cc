// `rfrecon check`: the capture checks alone (linearity, response, black level, saturation, exposure, bit depth, frame
// order) on a capture directory, printed, and as JSON with --json; exit 9 when they find a problem.
#include <cmath>
#include <cstdio>
#include <memory>
#include <string>

#include "host/capture/capture_checks.h"
#include "host/cli/capture_options.h"
#include "host/cli/commands.h"
#include "host/cli/exit_codes.h"
#include "host/core/atomic_file.h"
#include "host/core/output_path.h"
#include "host/transport/compute_transport.h"

namespace rfrecon::cli {

namespace {
struct CheckOptions {
  std::filesystem::path capture_dir;
  CaptureOptions capture;
  std::filesystem::path json;
  bool force = false;
};

void run_check(const CheckOptions& options) {
  const auto source = capture_source(options.capture);
  const auto manifest = transport::open_capture(options.capture_dir, source.layout, source.projector_size,
                                                source.frame_paths, source.bit_depth);
  const OutputPath json_output{options.json, "--json", options.force};
  if (!options.json.empty()) check_output_file(json_output, capture::capture_files(options.capture_dir, manifest));
  const auto result = capture::check_capture(options.capture_dir, manifest);
  if (!options.json.empty()) write_file_atomically(options.json, capture::to_json(result).dump(2) + "\n");
  std::printf("check: %s: %zu sampled pixels (%zu lit)\n", options.capture_dir.string().c_str(), result.sampled_pixels,
              result.lit_pixels);
  for (const auto& measure : capture::measures_of(result)) {
    if (std::isfinite(measure.value)) std::printf("  %-20s %10.4g %s\n", measure.name, measure.value, measure.unit);
  }
  for (const auto& finding : result.findings)
    std::printf("problem (%s): %s\n", finding.check.c_str(), finding.message.c_str());
  if (!result.findings.empty()) {
    throw CommandFailed(kExitCheck, std::to_string(result.findings.size()) + " capture problem(s) found");
  }
  std::printf("check: no problem found\n");
}
}  // namespace

void add_check_command(CLI::App& app) {
  auto options = std::make_shared<CheckOptions>();
  auto* command =
      app.add_subcommand("check", "Check a capture (linearity, response, black level, saturation, exposure, order)");
  command->add_option("capture_dir", options->capture_dir, "Capture directory")->required();
  add_capture_options(command, options->capture);
  command->add_option("--json", options->json, "Also write the measures and problems to this JSON");
  command->add_flag("--force", options->force, "Replace an existing --json file");
  command->callback([options] { run_check(*options); });
}

}  // namespace rfrecon::cli
