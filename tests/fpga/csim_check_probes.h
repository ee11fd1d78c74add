// The probe loops of csim_check_probes.cc, which csim_check_selftest.cc runs.
#pragma once

namespace rf_csim::probes {

struct WideWord {
  float value[16];  // 512 bits: one AXI beat
};

void accumulate(const float* x, float* out, int n, int claimed);
void prefix_sum(const float* x, float* out, int n);
void three_taps(const float* x, float* out, int n);
void two_reads_one_bundle(const float* x, float* out, int n);
void struct_fields(const float* x, float* out, int n);
void wide_word_sum(const WideWord* x, float* out, int n);

}  // namespace rf_csim::probes
