// What a reconstruction's summary.json records of its inputs: the camera's intrinsics and the options of the run.
#pragma once

#include <vector>

#include <nlohmann/json.hpp>

#include "calib/rig.h"
#include "host/cl/device_context.h"
#include "host/cl/kernel_entry.h"
#include "host/pipeline/reconstruct_scan.h"

namespace rfrecon::pipeline {

// The camera's intrinsics as OpenCV takes them (docs/formats.md): image_size [W, H], camera_matrix (3x3, rows),
// dist_coeffs (OpenCV's order) with their names (k1 k2 p1 p2 k3 ...).
nlohmann::json camera_intrinsics_json(const calib::StereoRig& rig);

// Every option of `rfrecon reconstruct`, named as on its command line, with the value the run used (defaults
// resolved): the files, method, devices (the names of those selected), entry with each device's `entries`,
// tile-timeout, the depth options, force.
nlohmann::json reconstruct_options_json(const ReconstructRequest& request,
                                        const std::vector<cl::DeviceContext>& devices,
                                        const std::vector<cl::KernelEntry>& entries);

}  // namespace rfrecon::pipeline
