// `rfrecon demo`: the whole pipeline on the synthetic rig (pipeline::run_demo) and one row per method.
#include <cstdio>

#include "host/cl/device_selection.h"
#include "host/cli/commands.h"
#include "host/pipeline/demo.h"
#include "sim/builtin_rigs.h"

namespace rfrecon::cli {

namespace {
struct DemoOptions {
  std::filesystem::path out = "out/demo";
  std::string rig;
  std::string devices;
  bool force = false;
};

void run_demo(const DemoOptions& options) {
  auto devices = cl::open_devices(options.devices);
  cl::ProgramCache programs;
  const auto demo = pipeline::run_demo(options.out, options.rig, options.force, devices, programs);
  std::printf("\n%s on the %s rig, calibrated from the simulated checkerboard poses (%.0f s in all):\n",
              demo.scene.c_str(), demo.rig.c_str(), demo.seconds);
  std::printf("%-12s %10s %12s %11s %11s\n", "method", "RMS mm", "% of side", "max mm", "coverage %");
  for (const auto& row : demo.methods) {
    std::printf("%-12s %10.4f %12.3f %11.3f %11.1f\n", row.method.c_str(), row.rms_mm, row.rms_percent, row.max_abs_mm,
                row.coverage_percent);
  }
  std::printf("(side %.0f mm; outputs, error maps and demo.json in %s)\n", demo.object_size_mm,
              options.out.string().c_str());
}
}  // namespace

void add_demo_command(CLI::App& app) {
  auto options = std::make_shared<DemoOptions>();
  auto* command = app.add_subcommand("demo", "Simulate, calibrate, reconstruct and evaluate the built-in cube");
  command->add_option("-o,--output", options->out, "Directory for every output (must not exist or be empty)")
      ->capture_default_str();
  command->add_flag("--force", options->force, "Replace an existing non-empty output directory");
  command->add_option(
      "--rig", options->rig,
      "Built-in rig to render with (rfrecon simulate --list; default " + std::string(sim::kDefaultRig) + ")");
  add_devices_option(command, options->devices);
  add_tile_timeout_option(command);
  command->callback([options] { run_demo(*options); });
}

}  // namespace rfrecon::cli
