// The macros of the row functions (depth/row_space.h) for one row in global memory, named RF_ROW_FN(name) = name.
// No include guard: opens an instance, which depth/row_kind_end.h closes.
#define RF_ROW_SPACE RF_GLOBAL
#define RF_ROW_FN(name) name
#include "depth/row_kind_scalar.h"
