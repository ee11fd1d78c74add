// The self-check's body, y = a * x + y, shared by kernels/selfcheck/axpy.cl and the HLS C++ top (hw/hls/).
#ifndef RFRECON_KERNELS_SELFCHECK_AXPY_H
#define RFRECON_KERNELS_SELFCHECK_AXPY_H

#include "common/portable.h"
#include "common/target.h"

RF_INLINE float rf_axpy_element(float a, float x, float y) { return RF_FMA(a, x, y); }

// The single work-item loop over the n elements.
RF_INLINE void rf_axpy_elements(unsigned n, float a, RF_GLOBAL const float* x, RF_GLOBAL float* y) {
  RF_PIPELINE_II(1)
  for (unsigned i = 0; i < n; ++i) {
    RF_HLS_PIPELINE
    y[i] = rf_axpy_element(a, x[i], y[i]);
  }
}

#endif  // RFRECON_KERNELS_SELFCHECK_AXPY_H
