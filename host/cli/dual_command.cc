// `rfrecon dual`: the dual image T^T 1 (projector view) or, with --primal, the primal image T 1 of a T.h5.
#include <spdlog/spdlog.h>

#include "host/cl/device_selection.h"
#include "host/cli/commands.h"
#include "host/pipeline/dual_image.h"

namespace rfrecon::cli {

namespace {
struct DualOptions {
  pipeline::DualImageRequest request;
  std::string devices;
};

void run_dual(const DualOptions& options) {
  const auto& request = options.request;
  auto devices = cl::open_devices(options.devices);
  cl::ProgramCache programs;
  const auto run = pipeline::dual_image(request, devices, programs);
  sched::log_reports({run.product.report});
  if (run.white > 0.0f) {
    spdlog::info("dual: {} scaled so that {:.6g} (99.9th percentile) is 65535", request.output.string(), run.white);
  }
  spdlog::info("{}: wrote {} image {}x{} to {}", request.primal ? "primal" : "dual",
               request.primal ? "camera" : "projector", run.size.width, run.size.height, request.output.string());
}
}  // namespace

void add_dual_command(CLI::App& app) {
  auto options = std::make_shared<DualOptions>();
  auto* command = app.add_subcommand("dual", "Dual image T^T 1 seen from the projector (or primal T 1) of a T.h5");
  command->add_option("transport", options->request.transport, "Compressed light transport (T.h5)")->required();
  command->add_option("-o,--output", options->request.output, "Image: .png (16-bit, scaled) or .tiff (float)")
      ->required();
  command->add_flag("--primal", options->request.primal, "Write the primal image T 1 (camera view) instead");
  command->add_option("--summary", options->request.summary,
                      "Also write the timing and per-device shares to this JSON");
  command->add_flag("--force", options->request.force, "Replace existing output and summary files");
  add_devices_option(command, options->devices);
  add_tile_timeout_option(command);
  command->callback([options] { run_dual(*options); });
}

}  // namespace rfrecon::cli
