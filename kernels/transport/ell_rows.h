// A camera pixel's ELL row of T as one word per array, in the layout of T's `indices` and `weights` (pixel c's RF_K
// entries at c * RF_K) and `correspondence` (its x, y at 2c): the single work-item loops read and write a pixel's row
// and correspondence in one access each (RF_K = 8: 256-bit words, one AXI beat; the NDRange entries view the same
// buffers as int and float arrays).
#ifndef RFRECON_KERNELS_TRANSPORT_ELL_ROWS_H
#define RFRECON_KERNELS_TRANSPORT_ELL_ROWS_H

#include "common/params.h"

typedef struct {  // NOLINT(modernize-use-using): shared with OpenCL C, which has no `using`
  int q[RF_K];    // projector pixel of each entry, -1 in an empty slot
} RfEllIndices;

typedef struct {  // NOLINT(modernize-use-using): shared with OpenCL C, which has no `using`
  float w[RF_K];  // each entry's weight, 0 in an empty slot
} RfEllWeights;

typedef struct {  // NOLINT(modernize-use-using): shared with OpenCL C, which has no `using`
  float x;
  float y;
} RfCorrespondence;

#endif  // RFRECON_KERNELS_TRANSPORT_ELL_ROWS_H
