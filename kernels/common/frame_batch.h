// The NDRange entries' batch of frames as RF_FRAME_BATCH buffers frame0, frame1, ... (the host lends each frame's own
// memory; unused ones repeat frame0): their parameters, and the array of them a kernel indexes.
#ifndef RFRECON_KERNELS_COMMON_FRAME_BATCH_H
#define RFRECON_KERNELS_COMMON_FRAME_BATCH_H

#include "common/params.h"

#define RF_FRAME_PARAMETER(f) __global const float* restrict frame##f
#define RF_FRAME_ARGUMENT(f) frame##f
#define RF_FRAME_PARAMETERS RF_EACH_FRAME(RF_FRAME_PARAMETER)
#define RF_FRAME_BUFFERS \
  { RF_EACH_FRAME(RF_FRAME_ARGUMENT) }

#endif  // RFRECON_KERNELS_COMMON_FRAME_BATCH_H
