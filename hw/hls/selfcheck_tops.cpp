// HLS C++ top of the self-check (Vitis 2023.1 and later): the body of axpy_single (kernels/selfcheck/axpy.h) behind
// AXI4 masters for x and y, AXI4-Lite for the rest, so that `rfrecon selfcheck` runs on a board built from the tops.
#define RF_TARGET_HLS  // kernels/common/target.h: the HLS directives

#include "hls/selfcheck_tops.h"

#include "hls/hls_top.h"
#include "selfcheck/axpy.h"

extern "C" void axpy_single(float a, const float* x, float* y, unsigned n) {
  RF_HLS_M_AXI(x, gmem0)
  RF_HLS_M_AXI(y, gmem1)
#pragma HLS INTERFACE mode = s_axilite port = return
  rf_axpy_elements(n, a, x, y);
}
