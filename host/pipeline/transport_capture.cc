// Capture to T.h5: transport stage, file writing and the summary JSON.
#include "host/pipeline/transport_capture.h"

#include <algorithm>
#include <optional>
#include <string>

#include <nlohmann/json.hpp>

#include "host/core/atomic_file.h"
#include "host/core/errors.h"
#include "host/core/image_file.h"
#include "host/core/limits.h"
#include "host/core/output_path.h"
#include "host/core/stage_clock.h"
#include "host/pipeline/transport_maps.h"
#include "host/transport/transport_file.h"

namespace rfrecon::pipeline {

namespace {
std::string threshold_text(const char* option, float value) {
  return std::string(option) + " " + (value > 0.0f ? std::to_string(value) : std::string("default"));
}

// "shadow 10 (at or below --black-threshold 0.02), ..., of N pixels": where the pixels went, and what set it.
std::string outcome_text(const transport::PixelOutcomeCounts& counts, const transport::Thresholds& thresholds) {
  using transport::PixelOutcome;
  const auto count = [&](PixelOutcome outcome) { return std::to_string(counts[static_cast<std::size_t>(outcome)]); };
  return "shadow " + count(PixelOutcome::kShadow) + " (lit at or below " +
         threshold_text("--black-threshold", thresholds.black) + "), out of range " + count(PixelOutcome::kOutOfRange) +
         ", undecided " + count(PixelOutcome::kUndecided) + " (Gray bits within " +
         threshold_text("--white-threshold", thresholds.white) + "), no signal " + count(PixelOutcome::kNoSignal) +
         " (dot entries at or below " + threshold_text("--noise-threshold", thresholds.noise) + ")";
}
}  // namespace

TransportFileRun transport_frames(const capture::FrameSource& frames, const capture::CaptureManifest& manifest,
                                  const transport::TransportSetup& setup, const cl::EntryChoice& entries, int readers,
                                  std::vector<cl::DeviceContext>& devices, cl::ProgramCache& programs) {
  const double camera_pixels = static_cast<double>(manifest.camera_size.area());
  check_memory(camera_pixels * (2.0 * 8.0 * setup.entries_per_pixel + 64.0),
               "the light transport of a " + size_text(manifest.camera_size) +
                   " camera with K = " + std::to_string(setup.entries_per_pixel));
  TransportFileRun file_run;
  file_run.run = transport::compute_transport_on_devices(frames, manifest, setup, devices, programs, entries, readers);
  file_run.outcomes = transport::count_outcomes(file_run.run.transport);
  const auto& flags = file_run.run.transport.flags;
  // Dot frames give correspondences around whatever code a pixel has, so a Gray code that no pixel decodes leaves
  // nothing to trust either.
  const bool gray_decoded =
      std::any_of(flags.begin(), flags.end(), [](std::uint8_t f) { return (f & transport::kFlagValid) != 0; });
  if (file_run.decoded_pixels() == 0 || !gray_decoded) {
    // The capture checks often know why (too dark, saturated, a gamma left on): they go into the message.
    std::string findings;
    for (const auto& finding : file_run.run.checks.findings) findings += " Capture check: " + finding.message + ".";
    throw ProcessingError(frames.name() + ": no camera pixel decoded (" +
                          outcome_text(file_run.outcomes, setup.thresholds) +
                          "); check that each pattern and its inverse are different captures of a lit scene, and "
                          "lower the threshold of the outcome that dominates." +
                          findings + " Nothing was written.");
  }
  return file_run;
}

TransportFileRun transport_capture(const TransportRequest& request, std::vector<cl::DeviceContext>& devices,
                                   cl::ProgramCache& programs) {
  request.entries.check_device_count(devices.size());
  const auto manifest =
      transport::open_capture(request.capture_dir, request.source.layout, request.source.projector_size,
                              request.source.frame_paths, request.source.bit_depth);
  const auto inputs = capture::capture_files(request.capture_dir, manifest);
  const OutputPath output{request.output, "--output", request.force};
  const OutputPath summary_output{request.summary, "--summary", request.force};
  const OutputPath maps_output{request.maps, "--maps", request.force};
  check_output_file(output, inputs);
  if (!request.summary.empty()) check_output_file(summary_output, inputs);
  if (!request.maps.empty()) check_output_directory(maps_output, inputs);
  check_distinct_outputs({output, summary_output, maps_output});

  TransportFileRun file_run = transport_frames(request.capture_dir, manifest, request.setup, request.entries,
                                               request.readers, devices, programs);
  AtomicFile t_file(request.output);
  StageClock clock;
  clock.time("write T.h5",
             [&] { transport::write_transport(file_run.run.transport, t_file.temp_path(), request.deflate_level); });
  file_run.run.timings.push_back(clock.timings().front());
  for (const auto& timing : file_run.run.timings) file_run.total_seconds += timing.seconds;
  std::optional<AtomicFile> summary_file;
  if (!request.summary.empty()) {
    nlohmann::json summary = {{"command", "transport"},
                              {"output", request.output.string()},
                              {"camera_pixels", file_run.run.transport.camera_pixels()},
                              {"decoded_pixels", file_run.decoded_pixels()},
                              {"total_seconds", file_run.total_seconds},
                              {"schedule", file_run.run.schedule},
                              {"capture_checks", capture::to_json(file_run.run.checks)}};
    for (std::size_t i = 0; i < transport::kPixelOutcomes; ++i) {
      summary["pixels"][transport::outcome_name(static_cast<transport::PixelOutcome>(i))] = file_run.outcomes[i];
    }
    if (const auto& gray = file_run.run.gray_decision) {
      summary["pixels"]["decoded_between_codes"] = gray->between_codes;
    }
    for (const auto& timing : file_run.run.timings) summary["stage_seconds"][timing.stage] = timing.seconds;
    summary_file.emplace(request.summary);
    summary_file->write(summary.dump(2) + "\n");
  }
  std::optional<StagingDirectory> maps_directory;
  if (!request.maps.empty()) {
    maps_directory.emplace(request.maps, request.force);
    write_transport_maps(file_run.run.transport, file_run.outcomes, maps_directory->path());
  }
  t_file.commit();
  if (summary_file) summary_file->commit();
  if (maps_directory) maps_directory->commit();
  return file_run;
}

}  // namespace rfrecon::pipeline
