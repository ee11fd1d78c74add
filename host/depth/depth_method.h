// The depth-method seam: a method turns a triangulated scan into depth on the camera grid, and is found by name in one
// registry that the CLI, the demo, the front door and Python enumerate (docs/architecture.md#extension-points).
#pragma once

#include <memory>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>
#include <opencv2/core.hpp>

#include "host/cl/device_context.h"
#include "host/cl/entry_choice.h"
#include "host/cl/program_cache.h"
#include "host/core/stage_clock.h"
#include "host/depth/rectification.h"
#include "host/depth/row_segmentation.h"
#include "host/depth/row_solvers.h"
#include "host/transport/transport_types.h"

namespace rfrecon::depth {

struct DepthOptions {
  std::string method = "fused";  // a registered method's name (depth_method_names())
  RectificationOptions rectification;
  SegmentationOptions segmentation;
  IntegrationOptions integration;
  FusionOptions fusion;
  cl::EntryChoice entries;  // kernel entry per device (default auto: cl::preferred_entry of each)
  // Noisy copies of T a method without a closed form for the frames' part of its depth sigma reruns on, and then also
  // reruns on moved rigs for the calibration's part (host/depth/sampled_sigma.h); 0: the frames' part is left unknown
  // and the calibration's is the triangulation's.
  int sigma_samples = 0;
};

// What a method is given: the scan, its triangulation on the camera grid, and where to run, time and report.
struct MethodScan {
  const transport::CompressedTransport& transport;
  const Rectification& rectification;
  const CameraGridTriangulation& triangulation;
  const DepthOptions& options;
  const std::string& rig_name;  // the calibration's file, for messages
  std::vector<cl::DeviceContext>& devices;
  cl::ProgramCache& programs;
  StageClock& clock;        // a method laps its own stages
  nlohmann::json& summary;  // a method adds its counts (summary.json)
};

class DepthMethod {
 public:
  DepthMethod() = default;
  DepthMethod(const DepthMethod&) = delete;
  DepthMethod& operator=(const DepthMethod&) = delete;
  DepthMethod(DepthMethod&&) = delete;
  DepthMethod& operator=(DepthMethod&&) = delete;
  virtual ~DepthMethod() = default;

  // Its --method name and one line for --help.
  virtual std::string name() const = 0;
  virtual std::string description() const = 0;
  // Whether it works along rectified rows on T's full rows (primal and dual images): it then needs the rig's row
  // lookups and a capture with the dot-grid scan.
  virtual bool needs_rows() const = 0;
  // The OpenCL programs it runs, built on every device before solve() (none for a host-only method).
  virtual std::vector<cl::ProgramRequest> programs(const transport::CompressedTransport& transport) const = 0;
  // Depth along the rectified optical axis (mm) at each camera pixel, CV_32F of the camera's size, NaN where none.
  // Throws ProcessingError when nothing is left to reconstruct, saying where the pixels went (pixel_losses.h).
  virtual cv::Mat solve(MethodScan& scan) const = 0;
  // One standard deviation (mm, along the rectified axis like solve's depth) of each pixel's depth that the frames'
  // noise causes, given solve's result; empty where the method does not propagate it (the default).
  virtual cv::Mat observation_sigma(const MethodScan& scan, const cv::Mat& z_rect_mm) const;
};

// Adds `method` to the registry (after the built-ins triangulate, integrate and fused). Throws std::invalid_argument
// for a name already registered. Register before opening devices: a method's kernels declare their private memory
// with cl::reserve_private_bytes where they are launched.
void register_depth_method(std::shared_ptr<const DepthMethod> method);
// The registered method of that name; throws InputError listing the names for an unknown one.
const DepthMethod& depth_method(const std::string& name);
// Every registered name, built-ins first, in registration order.
std::vector<std::string> depth_method_names();

}  // namespace rfrecon::depth
