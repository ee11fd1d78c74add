// `rfrecon transport`: decodes a capture and compresses its light transport into T.h5 on an OpenCL device.
#include <cstdio>

#include <spdlog/spdlog.h>

#include "host/cl/device_selection.h"
#include "host/cl/entry_choice.h"
#include "host/cli/capture_options.h"
#include "host/cli/commands.h"
#include "host/cli/number_checks.h"
#include "host/pipeline/transport_capture.h"

namespace rfrecon::cli {

namespace {
struct TransportOptions {
  pipeline::TransportRequest request;
  CaptureOptions capture;
  std::string devices;
};

void run_transport(TransportOptions options) {
  auto& request = options.request;
  request.source = capture_source(options.capture);
  auto devices = cl::open_devices(options.devices);
  const auto entries = request.entries.resolve(devices);  // a list of the wrong length: UsageError, exit 2
  for (std::size_t i = 0; i < devices.size(); ++i) {
    spdlog::info("transport: {} on {} (entry {})", request.capture_dir.string(), cl::describe(devices[i].info()),
                 cl::entry_name(entries[i]));
  }
  cl::ProgramCache programs;
  const auto file_run = pipeline::transport_capture(request, devices, programs);
  log_check_findings(file_run.run.checks, request.capture_dir.string());
  std::printf("transport: %zu of %zu camera pixels decoded", file_run.decoded_pixels(),
              file_run.run.transport.camera_pixels());
  if (const auto& gray = file_run.run.gray_decision) {
    std::printf(" (%zu between two adjacent codes)", gray->between_codes);
  }
  std::printf(", wrote %s\nno correspondence:", request.output.string().c_str());
  for (std::size_t i = 1; i < transport::kPixelOutcomes; ++i) {
    std::printf(" %s %zu%s", transport::outcome_name(static_cast<transport::PixelOutcome>(i)), file_run.outcomes[i],
                i + 1 < transport::kPixelOutcomes ? "," : "\n");
  }
  std::printf("stage timings:\n");
  for (const auto& timing : file_run.run.timings) {
    std::printf("  %-12s %8.3f s\n", timing.stage.c_str(), timing.seconds);
  }
  std::printf("  %-12s %8.3f s\nprograms: %s\n", "total", file_run.total_seconds,
              cl::describe(programs.builds(), programs.store()).c_str());
  sched::log_reports(file_run.run.schedule);
}
}  // namespace

void add_transport_command(CLI::App& app) {
  auto options = std::make_shared<TransportOptions>();
  auto* command = app.add_subcommand("transport", "Decode a capture and compress its light transport to T.h5");
  command->add_option("capture_dir", options->request.capture_dir, "Capture directory")->required();
  command->add_option("-o,--output", options->request.output, "Output file (T.h5)")->required();
  command->add_option("--summary", options->request.summary,
                      "Also write stage timings and per-device shares to this JSON");
  command->add_option("--maps", options->request.maps,
                      "Also write decoded.png (each pixel's projector column and row) and outcomes.png (why each "
                      "pixel without a correspondence has none) into this directory");
  command->add_flag("--force", options->request.force, "Replace existing output, summary and maps");
  add_capture_options(command, options->capture);
  add_devices_option(command, options->devices);
  add_tile_timeout_option(command);
  auto& setup = options->request.setup;
  command
      ->add_option("-k,--entries", setup.entries_per_pixel,
                   "Entries kept per camera pixel (K; a capture without dots keeps one)")
      ->check(CLI::Range(1, transport::kMaxEntriesPerPixel))
      ->capture_default_str();
  command
      ->add_option("--black-threshold", setup.thresholds.black,
                   "Lit when white - black exceeds this (linear, 1 = full scale)")
      ->check(finite_range(0.0, transport::kMaxThreshold))
      ->capture_default_str();
  command
      ->add_option("--white-threshold", setup.thresholds.white,
                   "Gray bit trusted when |pattern - inverse| exceeds this (linear; 0, the default: 4.5 DN at the "
                   "capture's bit depth); Gray-code-only captures also need 3 sigma of each pixel's noise and 2 % of "
                   "its white - black")
      ->check(finite_range(0.0, transport::kMaxThreshold));
  command
      ->add_option("--noise-threshold", setup.thresholds.noise,
                   "Transport entries at or below are dropped (linear; 0, the default: 2.5 DN at the capture's bit "
                   "depth)")
      ->check(finite_range(0.0, transport::kMaxThreshold));
  add_entry_option(command, options->request.entries);
  command->add_option("--readers", options->request.readers, "Threads reading frames ahead of the devices")
      ->check(CLI::Range(1, 64))
      ->capture_default_str();
  command->add_option("--deflate", options->request.deflate_level, "zlib level of T.h5's datasets, 0 for none")
      ->check(CLI::Range(0, 9))
      ->capture_default_str();
  command->callback([options] { run_transport(*options); });
}

}  // namespace rfrecon::cli
