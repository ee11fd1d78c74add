// The NDRange entries' batch of frames as RF_FRAME_BATCH buffers frame0, frame1, ... (the host lends each frame's own
// memory; unused ones repeat frame0): their parameters, the array of them a kernel indexes, and their samples made
// linear. Samples are RF_SAMPLE: float (linear already) or, built with -DRF_SAMPLE=uchar or ushort, the camera's raw
// samples, linear = (sample - black) * scale (capture::SampleMap; a float frame's map is 0, 1).
#ifndef RFRECON_KERNELS_COMMON_FRAME_BATCH_H
#define RFRECON_KERNELS_COMMON_FRAME_BATCH_H

#include "common/lanes.h"
#include "common/params.h"
#include "common/portable.h"

#ifndef RF_SAMPLE
#define RF_SAMPLE float
#endif

#define RF_FRAME_PARAMETER(f) __global const RF_SAMPLE* restrict frame##f
#define RF_FRAME_ARGUMENT(f) frame##f
#define RF_FRAME_PARAMETERS RF_EACH_FRAME(RF_FRAME_PARAMETER)
#define RF_FRAME_BUFFERS \
  { RF_EACH_FRAME(RF_FRAME_ARGUMENT) }

// As the host's capture::linearize_samples computes it.
typedef struct {
  float black;
  float scale;
} RfSampleMap;

// Sample c of `frame`, linear.
RF_INLINE float rf_linear_sample(__global const RF_SAMPLE* frame, uint c, RfSampleMap map) {
  return ((float)frame[c] - map.black) * map.scale;
}

// Samples c0 .. c0 + RF_LANES - 1 of `frame`, linear, one per vector lane.
RF_INLINE RF_LANES_REAL RF_LANES_FN(rf_linear_sample)(__global const RF_SAMPLE* frame, uint c0, RfSampleMap map) {
  return (RF_LANES_TO_REAL(RF_LANES_LOAD(0, frame + c0)) - map.black) * map.scale;
}

#endif  // RFRECON_KERNELS_COMMON_FRAME_BATCH_H
