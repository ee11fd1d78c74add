// `rfrecon reconstruct`: depth, normals, confidence and a point cloud from T.h5 and a calibrated rig.
#include <cstdio>

#include "host/cl/device_selection.h"
#include "host/cli/commands.h"
#include "host/cli/number_checks.h"
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
  request.depth.method = depth::parse_method(options.method);
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
  command->add_option("--method", options->method, "triangulate, integrate (reciprocity ODE) or fused")
      ->check(CLI::IsMember({"triangulate", "integrate", "fused"}))
      ->capture_default_str();
  command->add_flag("--force", options->request.force, "Replace an existing output directory");
  add_devices_option(command, options->devices);
  add_tile_timeout_option(command);
  add_entry_option(command, options->request.depth.entries);
  auto& depth = options->request.depth;
  command
      ->add_option("--epipolar-tolerance", depth.rectification.epipolar_tolerance_px,
                   "Reject correspondences further than this from their rectified row (px)")
      ->check(finite_range(0.01, 1000.0))
      ->capture_default_str();
  command
      ->add_option("--saturation", depth.rectification.saturation,
                   "Drop pixels with a T entry at or above this (linear, 1 = full scale)")
      ->check(finite_range(0.1, 1000.0))
      ->capture_default_str();
  command
      ->add_option("--edge-relative", depth.rectification.edge_relative,
                   "Drop pixels whose direct energy differs from a neighbour's by more than this fraction of their "
                   "own (albedo and shadow edges bias the correspondence)")
      ->check(finite_range(0.1, 1000.0))
      ->capture_default_str();
  command
      ->add_option("--edge-footprint", depth.rectification.edge_footprint_px2,
                   "Correct the correspondences on albedo and shadow edges for a camera-pixel footprint of this "
                   "second moment (px^2: 1/12 for a sharp pixel, plus the blur's variance; 0: off)")
      ->check(finite_range(0.0, 10.0))
      ->capture_default_str();
  command->add_option("--jump", depth.segmentation.jump_relative, "Relative depth step that ends a run")
      ->check(finite_range(0.001, 1000.0))
      ->capture_default_str();
  command->add_option("--crease", depth.segmentation.crease_deg, "Change of in-row slope that ends a run (deg)")
      ->check(finite_range(1.0, 180.0))
      ->capture_default_str();
  command->add_option("--passes", depth.integration.passes, "Shooting passes of the integration")
      ->check(CLI::Range(1, 20))
      ->capture_default_str();
  command->add_option("--iterations", depth.fusion.iterations, "Linearised solves of the fusion")
      ->check(CLI::Range(1, 20))
      ->capture_default_str();
  command->add_option("--sigma-disparity", depth.fusion.sigma_disparity_px, "Disparity noise, px (fusion weight)")
      ->check(finite_range(1e-4, 100.0))
      ->capture_default_str();
  command->add_option("--sigma-step", depth.fusion.sigma_step_mm, "ODE step error, mm (fusion weight)")
      ->check(finite_range(1e-4, 100.0))
      ->capture_default_str();
  command->callback([options] { run_reconstruct(*options); });
}

}  // namespace rfrecon::cli
