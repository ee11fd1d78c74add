// `rfrecon demo` as a library call: the whole pipeline on the synthetic rig. Renders the checkerboard poses and the
// anisotropic cube, builds T, calibrates from the poses (not from the true rig), reconstructs with the three methods
// and evaluates each against the truth.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "host/cl/device_context.h"
#include "host/cl/program_cache.h"

namespace rfrecon::pipeline {

struct DemoRow {
  std::string method;
  double rms_mm = 0.0;
  double rms_percent = 0.0;  // of the object's size
  double mean_abs_mm = 0.0;
  double max_abs_mm = 0.0;
  double coverage_percent = 0.0;
};

struct DemoRun {
  std::string scene;
  std::string rig;
  double object_size_mm = 0.0;
  std::vector<DemoRow> methods;  // each registered depth method (depth::depth_method_names())
  double seconds = 0.0;
  std::filesystem::path out_dir;
};

// Writes OUT/checkerboard-poses/, OUT/rig.yaml (+ report), OUT/cube-anisotropic/ (with T.h5), OUT/METHOD/ per method
// (with evaluation.json and error_map.png) and OUT/demo.json. OUT must be absent or empty unless `force` (then the
// demo's files replace those there); UsageError otherwise. `rig` names a built-in rig (sim/builtin_rigs.h); empty =
// the scenes' default.
DemoRun run_demo(const std::filesystem::path& out_dir, const std::string& rig, bool force,
                 std::vector<cl::DeviceContext>& devices, cl::ProgramCache& programs);

}  // namespace rfrecon::pipeline
