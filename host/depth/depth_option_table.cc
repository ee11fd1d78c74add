// The table of the depth stage's tuning options and the checks against it.
#include "host/depth/depth_option_table.h"

#include <cmath>
#include <sstream>

#include "host/core/errors.h"

namespace rfrecon::depth {

const std::vector<DepthOptionSpec>& depth_option_table() {
  static const std::vector<DepthOptionSpec> table{
      {"epipolar-tolerance", "Reject correspondences further than this from their rectified row (px)", 0.01, 1000.0,
       [](DepthOptions& o) { return &o.rectification.epipolar_tolerance_px; }, nullptr},
      {"saturation", "Drop pixels with a T entry at or above this (linear, 1 = full scale)", 0.1, 1000.0,
       [](DepthOptions& o) { return &o.rectification.saturation; }, nullptr},
      {"edge-relative",
       "Drop pixels whose direct energy differs from a neighbour's by more than this fraction of their own (albedo "
       "and shadow edges bias the correspondence)",
       0.1, 1000.0, [](DepthOptions& o) { return &o.rectification.edge_relative; }, nullptr},
      {"edge-footprint",
       "Correct the correspondences on albedo and shadow edges for a camera-pixel footprint of this second moment "
       "(px^2: 1/12 for a sharp pixel, plus the blur's variance; 0: off)",
       0.0, 10.0, [](DepthOptions& o) { return &o.rectification.edge_footprint_px2; }, nullptr},
      {"jump", "Relative depth step that ends a run", 0.001, 1000.0,
       [](DepthOptions& o) { return &o.segmentation.jump_relative; }, nullptr},
      {"crease", "Change of in-row slope that ends a run (deg)", 1.0, 180.0,
       [](DepthOptions& o) { return &o.segmentation.crease_deg; }, nullptr},
      {"passes", "Shooting passes of the integration", 1, 20, nullptr,
       [](DepthOptions& o) { return &o.integration.passes; }},
      {"iterations", "Linearised solves of the fusion", 1, 20, nullptr,
       [](DepthOptions& o) { return &o.fusion.iterations; }},
      {"sigma-disparity", "Disparity noise, px (fusion weight)", 1e-4, 100.0,
       [](DepthOptions& o) { return &o.fusion.sigma_disparity_px; }, nullptr},
      {"sigma-step", "ODE step error, mm (fusion weight)", 1e-4, 100.0,
       [](DepthOptions& o) { return &o.fusion.sigma_step_mm; }, nullptr},
      {"sigma-samples",
       "Noisy copies of T the method reruns on to measure the frames' part of each point's depth sigma where it has "
       "no closed form (integrate, fused; 0: left unknown); with a calibrated rig, also reruns it on the rig moved "
       "along its covariance for the calibration's part",
       0, 64, nullptr, [](DepthOptions& o) { return &o.sigma_samples; }},
  };
  return table;
}

namespace {
const DepthOptionSpec& spec_named(const std::string& name) {
  std::ostringstream names;
  for (const auto& spec : depth_option_table()) {
    if (name == spec.name) return spec;
    names << (names.tellp() > 0 ? ", " : "") << spec.name;
  }
  throw UsageError("unknown depth option '" + name + "' (" + names.str() + ")");
}

// A float option is compared as stored: 0.01 read into a float is just under the double 0.01.
double as_stored(const DepthOptionSpec& spec, double value) {
  return spec.real != nullptr ? static_cast<double>(static_cast<float>(value)) : value;
}

void check_value(const DepthOptionSpec& spec, double value) {
  const bool whole = spec.whole != nullptr;
  const double stored = as_stored(spec, value);
  const bool in_range =
      std::isfinite(value) && stored >= as_stored(spec, spec.low) && stored <= as_stored(spec, spec.high);
  if (!in_range || (whole && value != std::floor(value))) {
    std::ostringstream message;
    message << "depth option '" << spec.name << "' is " << value << ": " << (whole ? "a whole number " : "") << "from "
            << spec.low << " to " << spec.high << " is taken";
    throw UsageError(message.str());
  }
}
}  // namespace

void set_depth_option(DepthOptions& options, const std::string& name, double value) {
  const DepthOptionSpec& spec = spec_named(name);
  check_value(spec, value);
  if (spec.real != nullptr) {
    *spec.real(options) = static_cast<float>(value);
  } else {
    *spec.whole(options) = static_cast<int>(value);
  }
}

void check_depth_options(const DepthOptions& options) {
  DepthOptions copy = options;  // the accessors hand out pointers into a mutable struct
  for (const auto& spec : depth_option_table()) {
    check_value(spec, spec.real != nullptr ? static_cast<double>(*spec.real(copy)) : *spec.whole(copy));
  }
}

}  // namespace rfrecon::depth
