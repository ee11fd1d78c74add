// Run codes of a rectified row (one byte per pixel), shared by the depth kernels and the host that computes them
// (host/depth/row_segmentation.cc). A run is a stretch of pixels the ODE may cross; it always begins with
// RF_RUN_START, so a kernel never has to look at a masked neighbour.
#ifndef RFRECON_KERNELS_DEPTH_ROW_RUNS_H
#define RFRECON_KERNELS_DEPTH_ROW_RUNS_H

#define RF_RUN_MASKED 0    // no depth here (shadow, no correspondence, saturated, grazing)
#define RF_RUN_CONTINUE 1  // continues the run of the pixel on its left
#define RF_RUN_START 2     // first pixel of a run (after a mask, a depth jump or a crease)

#endif  // RFRECON_KERNELS_DEPTH_ROW_RUNS_H
