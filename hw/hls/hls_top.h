// What every HLS C++ top of hw/hls/ includes, after defining RF_TARGET_HLS: RF_HLS_M_AXI(argument, bundle), the
// argument's AXI4 master interface (and, for the C simulation's access check, its bundle: common/csim_hooks.h).
#pragma once

#include "common/target.h"

#define RF_HLS_PRAGMA_(x) _Pragma(#x)

#if defined(RF_CSIM_CHECK)
#define RF_HLS_M_AXI(argument, bundle_name)                                                      \
  RF_HLS_PRAGMA_(HLS INTERFACE mode = m_axi port = argument offset = slave bundle = bundle_name) \
  RF_CSIM_PORT(argument, bundle_name)
#else
#define RF_HLS_M_AXI(argument, bundle_name) \
  RF_HLS_PRAGMA_(HLS INTERFACE mode = m_axi port = argument offset = slave bundle = bundle_name)
#endif
