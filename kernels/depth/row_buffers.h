// The on-chip rows of the single work-item depth entries (kernels/depth/row_interleave.h): elements per row array
// and private bytes in all, from which the host also sizes CPU runtimes' worker-thread stacks
// (host/cl/device_context.cc).
#ifndef RFRECON_KERNELS_DEPTH_ROW_BUFFERS_H
#define RFRECON_KERNELS_DEPTH_ROW_BUFFERS_H

#include "common/params.h"

#define RF_INTEGRATE_BUFFER (RF_INTEGRATE_INTERLEAVE * RF_MAX_ROW_WIDTH)
#define RF_FUSE_BUFFER (RF_FUSE_INTERLEAVE * RF_MAX_ROW_WIDTH)
// The slopes of the fusion's forward sweep (two RK4 increments), each with its own copy of the projector rows.
#define RF_FUSE_SLOPES 8
// The integration holds 4 float rows and a byte row, the fusion 5 float rows, RF_FUSE_SLOPES (8) copies of the
// projector rows and a byte row.
#define RF_INTEGRATE_PRIVATE_BYTES \
  ((size_t)RF_INTEGRATE_INTERLEAVE * (size_t)RF_MAX_ROW_WIDTH * (4 * sizeof(float) + 1))
#define RF_FUSE_PRIVATE_BYTES ((size_t)RF_FUSE_INTERLEAVE * (size_t)RF_MAX_ROW_WIDTH * (13 * sizeof(float) + 1))

#endif  // RFRECON_KERNELS_DEPTH_ROW_BUFFERS_H
