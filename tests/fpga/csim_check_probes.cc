// Small pipelined loops with known accesses and dependences, built as the tops are for the access check (RF_CSIM_CHECK,
// ThreadSanitizer's instrumentation): what csim_check_selftest.cc expects the check to find in each.
#define RF_TARGET_HLS  // kernels/common/target.h: the HLS directives, here the check's hooks

#include "tests/fpga/csim_check_probes.h"

#include "hls/hls_top.h"

namespace rf_csim::probes {

// acc[i % 8] += x[i]: a dependence 8 iterations apart, claimed as `claimed` by RF_HLS_DEPENDENCE.
void accumulate(const float* x, float* out, int n, int claimed) {
  RF_HLS_M_AXI(x, gmem0)
  RF_HLS_M_AXI(out, gmem1)
  float acc[8];
  RF_ON_CHIP_RAM(acc)
  for (int k = 0; k < 8; ++k) acc[k] = 0.0f;
  for (int i = 0; i < n; ++i) {
    RF_HLS_PIPELINE
    RF_HLS_DEPENDENCE(acc, claimed)
    acc[i % 8] += x[i];
  }
  for (int k = 0; k < 8; ++k) out[k] = acc[k];
}

// a[i] = a[i - 1] + x[i] under Intel's `ivdep safelen(4)`: a dependence 1 iteration apart.
void prefix_sum(const float* x, float* out, int n) {
  RF_HLS_M_AXI(x, gmem0)
  RF_HLS_M_AXI(out, gmem1)
  float a[64];
  RF_ON_CHIP_RAM(a)
  a[0] = x[0];
  RF_IVDEP_SAFELEN(4)
  for (int i = 1; i < n; ++i) {
    RF_HLS_PIPELINE
    a[i] = a[i - 1] + x[i];
  }
  for (int i = 0; i < n; ++i) out[i] = a[i];
}

// out[i] = r[i] + r[i + 1] + r[i + 2]: three reads of one RAM per iteration.
void three_taps(const float* x, float* out, int n) {
  RF_HLS_M_AXI(x, gmem0)
  RF_HLS_M_AXI(out, gmem1)
  float r[66];
  RF_ON_CHIP_RAM(r)
  for (int i = 0; i < n + 2; ++i) r[i] = x[i];
  for (int i = 0; i < n; ++i) {
    RF_HLS_PIPELINE
    out[i] = r[i] + r[i + 1] + r[i + 2];
  }
}

// out[i] = x[i] + x[i + n]: two reads of one bundle per iteration.
void two_reads_one_bundle(const float* x, float* out, int n) {
  RF_HLS_M_AXI(x, gmem0)
  RF_HLS_M_AXI(out, gmem1)
  for (int i = 0; i < n; ++i) {
    RF_HLS_PIPELINE
    out[i] = x[i] + x[i + n];
  }
}

// Two fields of a struct array, each read and written per iteration: one RAM per field, two accesses each.
struct Pair {
  float sum;
  float product;
};
void struct_fields(const float* x, float* out, int n) {
  RF_HLS_M_AXI(x, gmem0)
  RF_HLS_M_AXI(out, gmem1)
  Pair pairs[4];
  RF_ON_CHIP_RAM(pairs)
  for (int k = 0; k < 4; ++k) pairs[k] = Pair{0.0f, 1.0f};
  for (int i = 0; i < n; ++i) {
    RF_HLS_PIPELINE
    RF_HLS_DEPENDENCE(pairs, 4)
    pairs[i % 4].sum += x[i];
    pairs[i % 4].product *= x[i];
  }
  for (int k = 0; k < 4; ++k) out[k] = pairs[k].sum + pairs[k].product;
}

// out[i] = the sum of x[i]'s 16 floats: one wide word of its argument, one beat per iteration.
void wide_word_sum(const WideWord* x, float* out, int n) {
  RF_HLS_M_AXI(x, gmem0)
  RF_HLS_M_AXI(out, gmem1)
  for (int i = 0; i < n; ++i) {
    RF_HLS_PIPELINE
    const WideWord word = x[i];
    float sum = 0.0f;
    for (const float v : word.value) sum += v;
    out[i] = sum;
  }
}

}  // namespace rf_csim::probes
