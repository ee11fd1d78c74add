// Address spaces of the rows the shared depth functions read, for OpenCL C and C++ alike.
//
// OpenCL C 1.2 has no generic address space, so a function reading a row must say whether the row is in global
// memory (the NDRange kernels, which read the tile's buffers directly) or on chip (the single work-item kernels,
// which copy each row into private buffers first). The files named *_rows.h hold such functions; the header that
// includes one (reciprocity.h, row_integration.h, row_fusion.h) instantiates it twice in OpenCL C:
//   RF_ROW_SPACE = RF_GLOBAL, RF_ROW_FN(name) = name                  rows in global memory
//   RF_ROW_SPACE = (private), RF_ROW_FN(name) = RF_ON_CHIP(name)      rows in on-chip buffers
// and once in C++ (no address spaces), where RF_ON_CHIP(name) is name itself.
#ifndef RFRECON_KERNELS_DEPTH_ROW_SPACE_H
#define RFRECON_KERNELS_DEPTH_ROW_SPACE_H

#include "common/portable.h"

#ifdef __OPENCL_VERSION__
#define RF_ON_CHIP(name) name##_on_chip
#else
#define RF_ON_CHIP(name) name
#endif

#endif  // RFRECON_KERNELS_DEPTH_ROW_SPACE_H
