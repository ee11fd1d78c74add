// Reads T and the rig, runs the depth stage, writes the output directory with the white frame as the PLY's colour.
#include "host/pipeline/reconstruct_scan.h"

#include <spdlog/spdlog.h>

#include "calib/rig.h"
#include "host/core/output_path.h"
#include "host/outputs/reconstruction_files.h"
#include "host/pipeline/reconstruct_summary.h"
#include "host/transport/transport_file.h"

namespace rfrecon::pipeline {

ReconstructRun reconstruct_transport(const transport::CompressedTransport& transport, const calib::StereoRig& rig,
                                     const std::string& rig_name, const ReconstructRequest& request,
                                     std::vector<cl::DeviceContext>& devices, cl::ProgramCache& programs) {
  const auto entries = request.depth.entries.resolve(devices);  // a list of the wrong length: UsageError
  for (std::size_t i = 0; i < devices.size(); ++i) {
    spdlog::info("reconstruct: on {} (entry {})", cl::describe(devices[i].info()), cl::entry_name(entries[i]));
  }
  ReconstructRun run;
  run.camera_pixels = transport.setup.camera_size.area();
  run.depth = depth::reconstruct_depth(transport, rig, rig_name, request.depth, devices, programs);
  run.depth.summary["transport_file"] = request.transport.string();
  run.depth.summary["calibration_file"] = request.rig.string();
  run.depth.summary["camera"] = camera_intrinsics_json(rig);
  run.depth.summary["options"] = reconstruct_options_json(request, devices, entries);
  if (!transport.white.empty()) {
    run.depth.maps.white = cv::Mat(transport.white, true).reshape(1, transport.setup.camera_size.height);
  }
  return run;
}

ReconstructRun reconstruct_scan(const ReconstructRequest& request, std::vector<cl::DeviceContext>& devices,
                                cl::ProgramCache& programs) {
  (void)request.depth.entries.resolve(devices);  // a list of the wrong length: UsageError before any work
  check_output_directory({request.out_dir, "--output", request.force}, {request.transport, request.rig});
  const auto transport = transport::read_transport(request.transport);
  const auto rig = calib::read_rig(request.rig);
  spdlog::info("reconstruct: {} from {} with {}", request.depth.method, request.transport.string(),
               request.rig.string());
  auto run = reconstruct_transport(transport, rig, request.rig.string(), request, devices, programs);
  outputs::write_reconstruction(run.depth.maps, run.depth.summary, request.out_dir, request.force);
  return run;
}

}  // namespace rfrecon::pipeline
