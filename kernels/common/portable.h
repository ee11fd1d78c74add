// What kernel bodies shared by OpenCL C and C++ (the HLS tops, host tests) need from either language: the global
// address space qualifier, inline functions and the float math they call.
#ifndef RFRECON_KERNELS_COMMON_PORTABLE_H
#define RFRECON_KERNELS_COMMON_PORTABLE_H

#ifdef __OPENCL_VERSION__
#define RF_GLOBAL __global
// Always inlined: PoCL otherwise compiles the depth ODE's slope as a call (found in a profile of the row solvers).
#define RF_INLINE inline __attribute__((always_inline))
#define RF_SQRT sqrt
#define RF_FABS fabs
#define RF_FMA fma
#define RF_MIN_INT min
#define RF_MAX_INT max
#else
#include <algorithm>
#include <cmath>
#include <cstddef>
#define RF_GLOBAL
#define RF_INLINE inline
#define RF_SQRT std::sqrt
#define RF_FABS std::fabs
#define RF_FMA std::fma
#define RF_MIN_INT std::min<int>
#define RF_MAX_INT std::max<int>
#endif

#endif  // RFRECON_KERNELS_COMMON_PORTABLE_H
