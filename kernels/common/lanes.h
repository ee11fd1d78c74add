// RF_LANES pixels side by side, one per vector lane: the compression's NDRange entry gives each work-item RF_LANES
// consecutive pixels, so that a CPU's vector units compute their window arithmetic together (docs/performance.md).
// RF_LANES sizes the host's launch; the vector type and the name suffix of functions on lanes are OpenCL C only.
#ifndef RFRECON_KERNELS_COMMON_LANES_H
#define RFRECON_KERNELS_COMMON_LANES_H

#define RF_LANES 8
#ifdef __OPENCL_VERSION__
#define RF_LANES_INT int8
#define RF_LANES_FN(name) name##_lanes
#endif

#endif  // RFRECON_KERNELS_COMMON_LANES_H
