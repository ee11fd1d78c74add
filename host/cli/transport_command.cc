// `rfrecon transport`: decodes a capture and compresses its light transport into T.h5 on an OpenCL device.
#include <chrono>
#include <cstdio>

#include <nlohmann/json.hpp>
#include <spdlog/spdlog.h>

#include "host/cl/device_selection.h"
#include "host/cli/capture_options.h"
#include "host/cli/commands.h"
#include "host/common/atomic_file.h"
#include "host/sched/report.h"
#include "host/transport/pipeline.h"
#include "host/transport/transport_file.h"

namespace rfrecon::cli {

namespace {
struct TransportOptions {
  std::filesystem::path capture_dir;
  std::filesystem::path output;
  std::filesystem::path summary;
  CaptureOptions capture;
  std::string devices;
  std::string entry = "ndrange";
  transport::TransportSetup setup;
};

void run_transport(const TransportOptions& options) {
  const auto manifest = open_capture(options.capture_dir, options.capture);
  auto devices = cl::open_devices(options.devices);
  for (const auto& device : devices) {
    spdlog::info("transport: {} frames from {} on {}", manifest.frames.size(), options.capture_dir.string(),
                 cl::describe(device.info()));
  }
  cl::ProgramCache programs;
  const auto entry =
      options.entry == "single" ? transport::KernelEntry::kSingleWorkItem : transport::KernelEntry::kNdRange;
  auto run =
      transport::compute_transport_on_devices(options.capture_dir, manifest, options.setup, devices, programs, entry);
  const auto start = std::chrono::steady_clock::now();
  transport::write_transport(run.transport, options.output);
  run.timings.push_back(
      {"write T.h5", std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count()});

  std::size_t valid = 0;
  for (const auto flags : run.transport.flags) valid += (flags & transport::kFlagValid) != 0 ? 1 : 0;
  std::printf("transport: %zu of %zu camera pixels decoded, wrote %s\nstage timings:\n", valid,
              run.transport.camera_pixels(), options.output.string().c_str());
  double total = 0.0;
  for (const auto& timing : run.timings) {
    std::printf("  %-12s %8.3f s\n", timing.stage.c_str(), timing.seconds);
    total += timing.seconds;
  }
  std::printf("  %-12s %8.3f s\n", "total", total);
  sched::log_reports(run.schedule);
  if (!options.summary.empty()) {
    nlohmann::json summary = {{"command", "transport"},
                              {"output", options.output.string()},
                              {"camera_pixels", run.transport.camera_pixels()},
                              {"decoded_pixels", valid},
                              {"total_seconds", total},
                              {"schedule", run.schedule}};
    for (const auto& timing : run.timings) summary["stage_seconds"][timing.stage] = timing.seconds;
    write_file_atomically(options.summary, summary.dump(2) + "\n");
  }
}
}  // namespace

void add_transport_command(CLI::App& app) {
  auto options = std::make_shared<TransportOptions>();
  auto* command = app.add_subcommand("transport", "Decode a capture and compress its light transport to T.h5");
  command->add_option("capture_dir", options->capture_dir, "Capture directory")->required();
  command->add_option("-o,--output", options->output, "Output file (T.h5)")->required();
  command->add_option("--summary", options->summary, "Also write stage timings and per-device shares to this JSON");
  add_capture_options(command, options->capture);
  add_devices_option(command, options->devices);
  auto& setup = options->setup;
  command->add_option("-k,--entries", setup.entries_per_pixel, "Entries kept per camera pixel (K)")
      ->check(CLI::Range(1, 64))
      ->capture_default_str();
  command->add_option("--black-threshold", setup.thresholds.black, "Lit when white - black exceeds this (linear)")
      ->capture_default_str();
  command->add_option("--white-threshold", setup.thresholds.white, "Gray bit trusted when |pattern - inverse| exceeds")
      ->capture_default_str();
  command->add_option("--noise-threshold", setup.thresholds.noise,
                      "Transport entries at or below are dropped (default: 2.5 DN at the capture's bit depth)");
  command->add_option("--entry", options->entry, "Kernel entry: ndrange or single (single work-item, FPGA)")
      ->check(CLI::IsMember({"ndrange", "single"}))
      ->capture_default_str();
  command->callback([options] { run_transport(*options); });
}

}  // namespace rfrecon::cli
