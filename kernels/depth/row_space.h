// The kinds of rows the shared depth functions work on, for OpenCL C and C++ alike.
//
// OpenCL C 1.2 has no generic address space and no templates, so the functions that read rows (the files named
// *_rows.h) are written once over a few macros and instantiated per kind of row, each kind's macros set by
// depth/row_kind_*.h:
//   rows in global memory, one row per call: RF_ROW_FN(name) = name (C++ references, HLS tops, segmentation);
//   rows in on-chip buffers (single work-item entries): RF_ROW_FN(name) = RF_ON_CHIP(name), OpenCL C only;
//   RF_LANES rows side by side, one per vector lane (NDRange entries): RF_ROW_FN(name) = RF_LANES_FN(name), OpenCL C
//   only, in the interleaved layout of depth/row_lanes.h.
// The macros of an instance: RF_ROW_SPACE (address space of the rows), RF_REAL and RF_INT (a row's float and integer
// values: float and int, or their RF_LANES-wide vectors), RF_TRUE (a set mask: 1, or -1 in every lane), RF_TO_REAL,
// RF_TO_INT (conversions), RF_LOAD, RF_STORE, RF_LOAD_CODE (element u of the row, the same u in every lane),
// RF_GATHER (element i, i per lane), RF_STORE_IF (a store per lane where its mask is set), RF_SELECT(type, mask,
// if_set, otherwise) (a choice per lane), RF_LANE_TYPE(name) (a struct of such values) and RF_ANY(mask) (whether any
// lane's mask is set, on lanes; 1 on one row, whose pipelines on FPGA boards must not branch): the one branch allowed,
// to skip work whose result no lane uses. Otherwise the shared code has no branch on a row's values: a condition is a
// mask, the result of a comparison (0 or 1 on scalars, 0 or -1 per lane on vectors), combined with & and |, and a
// choice is RF_SELECT, never ?: on a mask nor &&, || or !. On lanes RF_SELECT is OpenCL's select(), a call that the
// compiler keeps whole: ?: on a vector mask lets clang rewrite the choice into arithmetic on vectors of booleans (m ? x
// + 1 : x becomes x + zext(m)), which oclgrind 21.10 evaluates wrongly (zext of a true lane gives 255, its negation
// -2), so the kernels must not depend on it. For the same reason a builtin never mixes a vector and a scalar:
// oclgrind's min(int8, int) leaves 0 in lanes 2 to 7; min(i, (RF_INT)(n)) it gets right.
#ifndef RFRECON_KERNELS_DEPTH_ROW_SPACE_H
#define RFRECON_KERNELS_DEPTH_ROW_SPACE_H

#include "common/lanes.h"
#include "common/portable.h"

#ifdef __OPENCL_VERSION__
#define RF_ON_CHIP(name) name##_on_chip
#else
#define RF_ON_CHIP(name) name
#endif

#endif  // RFRECON_KERNELS_DEPTH_ROW_SPACE_H
