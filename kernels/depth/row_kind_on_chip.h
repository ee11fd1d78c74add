// The macros of the row functions (depth/row_space.h) for one row in an on-chip buffer of a single work-item kernel,
// named RF_ON_CHIP(name). OpenCL C only. No include guard: opens an instance, which depth/row_kind_end.h closes.
#define RF_ROW_SPACE
#define RF_ROW_FN(name) RF_ON_CHIP(name)
#include "depth/row_kind_scalar.h"
