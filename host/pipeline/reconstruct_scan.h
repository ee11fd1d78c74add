// `rfrecon reconstruct` as a library call: T.h5 and rig.yaml to a reconstruction directory.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "host/depth/reconstruct_depth.h"

namespace rfrecon::pipeline {

struct ReconstructRequest {
  std::filesystem::path transport;  // T.h5
  std::filesystem::path rig;        // rig.yaml
  depth::DepthOptions depth;
  std::filesystem::path out_dir;  // written whole (outputs::write_reconstruction)
  bool force = false;             // replace an existing out_dir
};

struct ReconstructRun {
  depth::DepthRun depth;  // summary with transport_file, calibration_file, camera (intrinsics) and options added
  int camera_pixels = 0;
};

// The depth stage of reconstruct_scan on a transport and rig in memory (`rig_name` names the rig in messages), with
// the summary's additions (request's files, camera, options) and T's white frame; writes nothing.
ReconstructRun reconstruct_transport(const transport::CompressedTransport& transport, const calib::StereoRig& rig,
                                     const std::string& rig_name, const ReconstructRequest& request,
                                     std::vector<cl::DeviceContext>& devices, cl::ProgramCache& programs);

// Throws UsageError before any work when out_dir is not a directory, holds an input, or is not empty without
// force, or when a per-device depth.entries list does not have one entry per device; InputError naming the file (bad
// T.h5 or rig, sizes that differ, a rig that cannot be rectified) and ProcessingError when nothing can be
// reconstructed; out_dir is then untouched.
ReconstructRun reconstruct_scan(const ReconstructRequest& request, std::vector<cl::DeviceContext>& devices,
                                cl::ProgramCache& programs);

}  // namespace rfrecon::pipeline
