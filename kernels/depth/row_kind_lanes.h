// The macros of the row functions (depth/row_space.h) for RF_LANES rows in global memory, one per vector lane, in the
// interleaved layout of depth/row_lanes.h, named RF_LANES_FN(name). OpenCL C only. No include guard: opens an
// instance, which depth/row_kind_end.h closes.
#define RF_ROW_SPACE RF_GLOBAL
#define RF_ROW_FN(name) RF_LANES_FN(name)
#define RF_REAL RF_LANES_REAL
#define RF_TRUE ((RF_LANES_INT)(-1))
#define RF_INT RF_LANES_INT
#define RF_TO_REAL(x) RF_LANES_TO_REAL(x)
#define RF_TO_INT(x) RF_LANES_TO_INT(x)
#define RF_LOAD(row, u) RF_LANES_LOAD(u, row)
#define RF_GATHER(row, i) rf_lanes_gather(row, i)
#define RF_LOAD_CODE(row, u) RF_LANES_TO_INT(RF_LANES_LOAD(u, row))
#define RF_STORE(row, u, value) RF_LANES_STORE(value, u, row)
#define RF_STORE_IF(row, mask, i, value) rf_lanes_store_if(row, mask, i, value)
#define RF_SELECT(type, mask, if_set, otherwise) select((type)(otherwise), (type)(if_set), (mask))
#define RF_ANY(mask) any(mask)
#define RF_LANE_TYPE(name) RF_LANES_FN(name)
