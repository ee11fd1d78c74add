// Cuts rectified rows into runs the reciprocity ODE may cross: masked pixels, depth jumps (occlusion boundaries) and
// creases (the surface orientation the ODE gives changes abruptly) end a run.
#pragma once

#include "host/depth/rectified_rows.h"

namespace rfrecon::depth {

struct SegmentationOptions {
  float jump_relative = 0.01f;  // triangulated depths of neighbours differing by more than this fraction: a jump
  float crease_deg = 12.0f;     // in-row surface slopes of neighbours differing by more than this angle: a crease
};

struct SegmentationStats {
  int usable = 0;          // pixels with signal, a triangulated depth and a well-posed ODE
  int runs = 0;            // runs (each starts with RF_RUN_START)
  int jumps = 0;           // runs started at a depth jump
  int creases = 0;         // runs started at a crease
  int ode_breakdowns = 0;  // pixels masked because the ODE breaks down there (no dual signal, grazing angle)
};

// Fills rows.runs from rows.e_cam, rows.e_proj and rows.z_tri.
SegmentationStats segment_rows(RectifiedRows& rows, const SegmentationOptions& options);

}  // namespace rfrecon::depth
