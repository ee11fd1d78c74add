// Closes an instance of the row functions opened by depth/row_kind_*.h. No include guard.
#undef RF_ROW_SPACE
#undef RF_ROW_FN
#undef RF_REAL
#undef RF_INT
#undef RF_TRUE
#undef RF_TO_REAL
#undef RF_TO_INT
#undef RF_LOAD
#undef RF_GATHER
#undef RF_LOAD_CODE
#undef RF_STORE
#undef RF_STORE_IF
#undef RF_SELECT
#undef RF_ANY
#undef RF_LANE_TYPE
