// The inputs of the row solvers on the rectified grid: normalised primal and dual rows, triangulated depth and run
// codes, with the rectified geometry. Built by host/depth/rectification.h, consumed by host/depth/row_solvers.h.
#pragma once

#include <cstdint>
#include <vector>

#include "kernels/depth/reciprocity.h"

namespace rfrecon::depth {

struct RectifiedRows {
  RfRectifiedRig rig{};            // f, principal points (px) and projector offset b (mm) of the rectified rig
  int width = 0;                   // rectified camera image
  int height = 0;                  // rectified rows (camera and projector share them)
  int proj_width = 0;              // rectified projector image width
  std::vector<float> e_cam;        // height x width: primal image / camera pixel solid angle, NaN where unusable
  std::vector<float> e_proj;       // height x proj_width: dual image / projector pixel solid angle, 0 where none
  std::vector<float> z_tri;        // height x width: triangulated depth (rectified frame, mm), NaN where none
  std::vector<std::uint8_t> runs;  // height x width: RF_RUN_* codes (kernels/depth/row_runs.h)

  std::size_t pixels() const { return static_cast<std::size_t>(width) * static_cast<std::size_t>(height); }
  float beta(int row) const { return (static_cast<float>(row) - rig.cy) / rig.f; }
};

}  // namespace rfrecon::depth
