// What kernel bodies shared by OpenCL C and C++ (the HLS tops, host tests) need from either language: the global
// address space qualifier, inline functions and the float math they call.
#ifndef RFRECON_KERNELS_COMMON_PORTABLE_H
#define RFRECON_KERNELS_COMMON_PORTABLE_H

#ifdef __OPENCL_VERSION__
#define RF_GLOBAL __global
// Always inlined: PoCL otherwise compiles the depth ODE's slope as a call (docs/performance.md, "Row solvers").
#define RF_INLINE inline __attribute__((always_inline))
#define RF_SQRT sqrt
#define RF_FABS fabs
#define RF_FMA fma
// In the row loops of the depth kernels: the NDRange entries' work-items, one row each, advance in step, a barrier per
// iteration, so that PoCL runs the work-group's rows side by side within each iteration and their slope chains
// overlap (docs/performance.md, "Row solvers"). Every work-item of a group reaches each barrier: the host pads the
// rows to whole work-groups. Nothing in C++.
#define RF_ROWS_IN_STEP() barrier(CLK_LOCAL_MEM_FENCE)
#else
#include <cmath>
#include <cstddef>
#define RF_GLOBAL
#define RF_INLINE inline
#define RF_SQRT std::sqrt
#define RF_FABS std::fabs
#define RF_FMA std::fma
#define RF_ROWS_IN_STEP()
#endif

#endif  // RFRECON_KERNELS_COMMON_PORTABLE_H
