// RF_LANES pixels or rows side by side, one per vector lane: the NDRange entries of the compression and of the depth
// row solvers give each work-item RF_LANES of them, so that a CPU's vector units compute them together
// (docs/performance.md). The types, conversions and the name suffix of functions on lanes; OpenCL C only but
// RF_LANES, which the host uses to size launches.
#ifndef RFRECON_KERNELS_COMMON_LANES_H
#define RFRECON_KERNELS_COMMON_LANES_H

#define RF_LANES 8
#ifdef __OPENCL_VERSION__
#define RF_LANES_REAL float8
#define RF_LANES_INT int8
#define RF_LANES_TO_REAL(x) convert_float8(x)
#define RF_LANES_TO_INT(x) convert_int8(x)
#define RF_LANES_LOAD(u, row) vload8(u, row)
#define RF_LANES_STORE(value, u, row) vstore8(value, u, row)
#define RF_LANES_FN(name) name##_lanes
#endif

#endif  // RFRECON_KERNELS_COMMON_LANES_H
