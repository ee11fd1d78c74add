// Capture to T.h5: transport stage, file writing and the summary JSON.
#include "host/pipeline/transport_capture.h"

#include <nlohmann/json.hpp>

#include "host/core/atomic_file.h"
#include "host/core/stage_clock.h"
#include "host/transport/transport_file.h"

namespace rfrecon::pipeline {

TransportFileRun transport_capture(const TransportRequest& request, std::vector<cl::DeviceContext>& devices,
                                   cl::ProgramCache& programs) {
  const auto manifest =
      transport::open_capture(request.capture_dir, request.source.layout, request.source.projector_size);
  TransportFileRun file_run;
  file_run.run = transport::compute_transport_on_devices(request.capture_dir, manifest, request.setup, devices,
                                                         programs, request.entry);
  StageClock clock;
  clock.time("write T.h5", [&] { transport::write_transport(file_run.run.transport, request.output); });
  file_run.run.timings.push_back(clock.timings().front());
  for (const auto flags : file_run.run.transport.flags) {
    file_run.decoded_pixels += (flags & transport::kFlagValid) != 0 ? 1 : 0;
  }
  for (const auto& timing : file_run.run.timings) file_run.total_seconds += timing.seconds;
  if (!request.summary.empty()) {
    nlohmann::json summary = {{"command", "transport"},
                              {"output", request.output.string()},
                              {"camera_pixels", file_run.run.transport.camera_pixels()},
                              {"decoded_pixels", file_run.decoded_pixels},
                              {"total_seconds", file_run.total_seconds},
                              {"schedule", file_run.run.schedule}};
    for (const auto& timing : file_run.run.timings) summary["stage_seconds"][timing.stage] = timing.seconds;
    write_file_atomically(request.summary, summary.dump(2) + "\n");
  }
  return file_run;
}

}  // namespace rfrecon::pipeline
