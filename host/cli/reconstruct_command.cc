// `rfrecon reconstruct`: depth, normals, confidence and a point cloud from T.h5 and a calibrated rig.
#include <cstdio>

#include "host/cl/device_selection.h"
#include "host/cli/commands.h"
#include "host/cli/number_checks.h"
#include "host/depth/depth_method.h"
#include "host/depth/depth_option_table.h"
#include "host/pipeline/reconstruct_scan.h"

namespace rfrecon::cli {

namespace {
struct ReconstructOptions {
  pipeline::ReconstructRequest request;
  std::string method = "fused";
  std::string devices;
};

void run_reconstruct(ReconstructOptions options) {
  auto& request = options.request;
  request.depth.method = options.method;
  auto devices = cl::open_devices(options.devices);
  cl::ProgramCache programs;
  const auto run = pipeline::reconstruct_scan(request, devices, programs);
  const auto& summary = run.depth.summary;
  std::printf("reconstruct (%s): %d of %d camera pixels, wrote %s\nstage timings:\n", options.method.c_str(),
              summary["reconstructed_pixels"].get<int>(), run.camera_pixels, request.out_dir.string().c_str());
  double total = 0.0;
  for (const auto& timing : summary["timings"]) {
    std::printf("  %-24s %8.3f s\n", timing["stage"].get<std::string>().c_str(), timing["seconds"].get<double>());
    total += timing["seconds"].get<double>();
  }
  std::printf("  %-24s %8.3f s\nprograms: %s\n", "total", total,
              cl::describe(programs.builds(), programs.store()).c_str());
}
}  // namespace

void add_reconstruct_command(CLI::App& app) {
  auto options = std::make_shared<ReconstructOptions>();
  auto* command = app.add_subcommand("reconstruct", "Depth, normals and a point cloud from T.h5 and rig.yaml");
  command->add_option("transport", options->request.transport, "Compressed light transport (T.h5)")->required();
  command->add_option("--calib", options->request.rig, "Calibrated rig (rig.yaml from `rfrecon calibrate`)")
      ->required();
  command->add_option("-o,--output", options->request.out_dir, "Output directory (docs/formats.md)")->required();
  std::string methods;
  for (const auto& name : depth::depth_method_names()) {
    methods += (methods.empty() ? "" : "; ") + name + ": " + depth::depth_method(name).description();
  }
  command->add_option("--method", options->method, "Depth method (" + methods + ")")
      ->check(CLI::IsMember(depth::depth_method_names()))
      ->capture_default_str();
  command->add_flag("--force", options->request.force, "Replace an existing output directory");
  add_devices_option(command, options->devices);
  add_tile_timeout_option(command);
  add_entry_option(command, options->request.depth.entries);
  for (const auto& spec : depth::depth_option_table()) {
    const std::string flag = std::string("--") + spec.name;
    if (spec.real != nullptr) {
      command->add_option(flag, *spec.real(options->request.depth), spec.help)
          ->check(finite_range(spec.low, spec.high))
          ->capture_default_str();
    } else {
      command->add_option(flag, *spec.whole(options->request.depth), spec.help)
          ->check(CLI::Range(static_cast<int>(spec.low), static_cast<int>(spec.high)))
          ->capture_default_str();
    }
  }
  command->callback([options] { run_reconstruct(*options); });
}

}  // namespace rfrecon::cli
