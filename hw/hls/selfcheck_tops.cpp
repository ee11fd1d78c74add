// HLS C++ top of the self-check (Vitis 2023.1 and later): the body of axpy_single (kernels/selfcheck/axpy.h) behind
// AXI4 masters for x and y, AXI4-Lite for the rest, so that `rfrecon selfcheck` runs on a board built from the tops.
#define RF_TARGET_HLS  // kernels/common/target.h: emit the HLS loop directives

#include "hls/selfcheck_tops.h"

#include "selfcheck/axpy.h"

extern "C" void axpy_single(float a, const float* x, float* y, unsigned n) {
#pragma HLS INTERFACE mode = m_axi port = x offset = slave bundle = gmem0
#pragma HLS INTERFACE mode = m_axi port = y offset = slave bundle = gmem1
#pragma HLS INTERFACE mode = s_axilite port = return
  rf_axpy_elements(n, a, x, y);
}
