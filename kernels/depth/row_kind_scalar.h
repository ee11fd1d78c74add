// The macros of the row functions (depth/row_space.h) shared by the kinds of one row per call (depth/row_kind_global.h,
// depth/row_kind_on_chip.h): scalar values, plain loads and stores, ?: for RF_SELECT. No include guard: included by
// those files, after their RF_ROW_SPACE and RF_ROW_FN.
#define RF_REAL float
#define RF_TRUE 1
#define RF_INT int
#define RF_TO_REAL(x) ((float)(x))
#define RF_TO_INT(x) ((int)(x))
#define RF_LOAD(row, u) ((row)[u])
#define RF_GATHER(row, i) ((row)[i])
#define RF_LOAD_CODE(row, u) ((int)(row)[u])
#define RF_STORE(row, u, value) ((row)[u] = (value))
#define RF_STORE_IF(row, mask, i, value) \
  do {                                   \
    if (mask) (row)[i] = (value);        \
  } while (0)
#define RF_SELECT(type, mask, if_set, otherwise) ((mask) ? (type)(if_set) : (type)(otherwise))
#define RF_ANY(mask) 1
#define RF_LANE_TYPE(name) name
