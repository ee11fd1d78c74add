// The HLS C++ top of the self-check kernel for Vitis 2023.1 and later (selfcheck_tops.cpp): the single work-item body
// of kernels/selfcheck/axpy.h, with the arguments of axpy.cl's axpy_single. Declared for its C simulation.
#pragma once

extern "C" void axpy_single(float a, const float* x, float* y, unsigned n);
