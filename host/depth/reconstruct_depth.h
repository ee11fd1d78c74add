// The depth stage as one call: from a compressed T and a calibrated rig to camera-grid depth, points, normals and
// confidence by triangulation, reciprocity integration (the paper's method) or their fusion.
#pragma once

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "calib/rig.h"
#include "host/cl/device_context.h"
#include "host/cl/entry_choice.h"
#include "host/cl/program_cache.h"
#include "host/depth/rectification.h"
#include "host/depth/row_segmentation.h"
#include "host/depth/row_solvers.h"
#include "host/outputs/reconstruction.h"
#include "host/transport/transport_types.h"

namespace rfrecon::depth {

enum class Method { kTriangulate, kIntegrate, kFused };

// "triangulate", "integrate", "fused".
std::string method_name(Method method);
// Throws InputError listing the names for an unknown one.
Method parse_method(const std::string& name);

struct DepthOptions {
  Method method = Method::kFused;
  RectificationOptions rectification;
  SegmentationOptions segmentation;
  IntegrationOptions integration;
  FusionOptions fusion;
  cl::EntryChoice entries;  // kernel entry per device (default auto: cl::preferred_entry of each)
};

struct DepthRun {
  outputs::Reconstruction maps;
  nlohmann::json summary;  // method, options, sizes, counts, per-stage seconds
};

// Throws InputError (sizes of T and rig differ, rig cannot be rectified; `rig_name` names the file) and
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
