// The depth stage as one call: from a compressed T and a calibrated rig to camera-grid depth, points, normals and
// confidence by one of the registered depth methods (depth_method.h): triangulation, reciprocity integration (the
// paper's method), their fusion, or one registered from outside.
#pragma once

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "calib/rig.h"
#include "host/depth/depth_method.h"
#include "host/outputs/reconstruction.h"

namespace rfrecon::depth {

struct DepthRun {
  outputs::Reconstruction maps;
  nlohmann::json summary;  // method, options, sizes, counts, per-stage seconds
};

// Throws InputError (unknown method, sizes of T and rig differ, rig cannot be rectified; `rig_name` names the file) and
// ProcessingError (nothing left to reconstruct: every pixel masked), UsageError (before any work) when a per-device
// options.entries list does not match `devices`. Kernels run on `devices` (at least one), each with its entry.
DepthRun reconstruct_depth(const transport::CompressedTransport& transport, const calib::StereoRig& rig,
                           const std::string& rig_name, const DepthOptions& options,
                           std::vector<cl::DeviceContext>& devices, cl::ProgramCache& programs);

// The same with the rig's rectification and per-pixel lookups computed beforehand (depth_rectification(rig, ...)), as
// a scanner making many scans with one calibration does: the first form spends the stage "rig geometry" on them.
DepthRun reconstruct_depth(const transport::CompressedTransport& transport, const calib::StereoRig& rig,
                           const Rectification& rectification, const std::string& rig_name, const DepthOptions& options,
                           std::vector<cl::DeviceContext>& devices, cl::ProgramCache& programs);

}  // namespace rfrecon::depth
