// The single work-item entries' batch of frames, pixel-major: pixel c's RF_FRAME_BATCH linear samples side by side,
// one wide word per pixel (RfFrameSamples: 16 floats, one 512-bit AXI beat, at the default batch), so that a pipelined
// pixel loop reads its batch in one access (host/transport/device_frames.h writes it so). Unused slots hold anything.
#ifndef RFRECON_KERNELS_COMMON_FRAME_SAMPLES_H
#define RFRECON_KERNELS_COMMON_FRAME_SAMPLES_H

#include "common/params.h"

typedef struct {  // NOLINT(modernize-use-using): shared with OpenCL C, which has no `using`
  float sample[RF_FRAME_BATCH];
} RfFrameSamples;

#endif  // RFRECON_KERNELS_COMMON_FRAME_SAMPLES_H
