# The kernels' compile-time parameters, written once in the table below, and rfrecon_configure_kernel_params(OUT_DIR),
# which checks them and writes from the table OUT_DIR/kernels/common/params.h (kernels/common/params.h.in: the
# kernels' macros and the host's RF_PARAMETERS_JSON) and OUT_DIR/kernels/common/params.json (the "parameters" object
# of an FPGA binary's manifest, hw/cmake/WriteManifest.cmake). The host build (cmake/EmbedKernels.cmake) and the hw/
# flows both call it, so a board binary and the host that loads it agree on the values unless they were configured
# differently, which the binary's manifest then shows and the host refuses (docs/fpga.md). A new parameter is one
# rfrecon_kernel_param line.
if(DEFINED RFRECON_ROW_INTERLEAVE)
  message(FATAL_ERROR "RFRECON_ROW_INTERLEAVE is gone: each depth kernel has its own interleave, "
                      "RFRECON_INTEGRATE_INTERLEAVE and RFRECON_FUSE_INTERLEAVE (docs/fpga.md); remove it from the cache "
                      "(cmake -U RFRECON_ROW_INTERLEAVE)")
endif()

# A board preset (hw/boards/<RFRECON_FPGA_BOARD>.cmake) sizes parameters for its board with RFRECON_PRESET_<NAME>: in a
# build configured with that board, the host's and the flow's RFRECON_<NAME> default to it, and take it again whenever
# the board changes; a -DRFRECON_<NAME>= given since overrides it (scripts/fpga_budget.py --set tells whether it fits).
if(RFRECON_FPGA_BOARD AND EXISTS ${CMAKE_CURRENT_LIST_DIR}/../hw/boards/${RFRECON_FPGA_BOARD}.cmake)
  include(${CMAKE_CURRENT_LIST_DIR}/../hw/boards/${RFRECON_FPGA_BOARD}.cmake)
endif()
if(DEFINED CACHE{RFRECON_KERNEL_PARAMS_BOARD} AND NOT "$CACHE{RFRECON_KERNEL_PARAMS_BOARD}" STREQUAL
                                                      "${RFRECON_FPGA_BOARD}")
  message(STATUS "Kernel parameters: the board changed to '${RFRECON_FPGA_BOARD}', its preset's values apply")
  set(rfrecon_board_changed TRUE)
else()
  set(rfrecon_board_changed FALSE)
endif()
# rfrecon_param_cache(VAR DEFAULT HELP): the cache option VAR, the preset's value (VAR with PRESET_ after RFRECON_) in
# place of DEFAULT where the preset has one, and forced when the board changed.
macro(rfrecon_param_cache var default help)
  string(REPLACE "RFRECON_" "RFRECON_PRESET_" rfrecon_preset_var ${var})
  if(DEFINED ${rfrecon_preset_var})
    set(rfrecon_param_default "${${rfrecon_preset_var}}")
  else()
    set(rfrecon_param_default "${default}")
  endif()
  if(rfrecon_board_changed)
    set(${var} "${rfrecon_param_default}" CACHE STRING "${help}" FORCE)
  else()
    set(${var} "${rfrecon_param_default}" CACHE STRING "${help}")
  endif()
endmacro()

# rfrecon_kernel_param(NAME DEFAULT MIN MAX OVERRIDABLE|FIXED HELP): the integer RF_NAME, set by the cache option
# RFRECON_NAME in [MIN, MAX] (the host's bounds). OVERRIDABLE: a program built from source on a CPU or GPU may be
# given another value with -DRF_NAME=; FIXED: the host's own code depends on it.
set(rfrecon_kernel_param_names "")
macro(rfrecon_kernel_param name default min max kind help)
  rfrecon_param_cache(RFRECON_${name} ${default} "${help}")
  list(APPEND rfrecon_kernel_param_names ${name})
  set(rfrecon_kernel_param_${name}_range ${min} ${max})
  set(rfrecon_kernel_param_${name}_kind ${kind})
  set(rfrecon_kernel_param_${name}_help "${help}")
endmacro()
rfrecon_kernel_param(K 8 1 64 OVERRIDABLE "entries per camera pixel of the compressed transport (ELL rows)")
rfrecon_kernel_param(INTEGRATE_INTERLEAVE 160 1 1024 OVERRIDABLE
                     "rows the single work-item integration interleaves, one RK4 slope per iteration (default: the \
latency in clocks of one slope, docs/fpga.md)")
rfrecon_kernel_param(FUSE_INTERLEAVE 32 1 1024 OVERRIDABLE
                     "rows the single work-item fusion interleaves, one pixel per iteration (default: the latency in \
clocks of the forward sweep's step)")
rfrecon_kernel_param(MAX_ROW_WIDTH 4096 1 16384 OVERRIDABLE
                     "the widest row (camera or projector pixels) a kernel keeps on chip")
rfrecon_kernel_param(FRAME_BATCH 16 2 64 FIXED  # a Gray pair per batch at least
                     "dot-grid frames the compression takes per launch, each pixel's ELL row kept in registers \
across them")

# RF_DOT_SPACINGS, the one list: the dot-grid spacings s the kernels support.
set(rfrecon_default_dot_spacings "")
foreach(s RANGE 2 64)
  list(APPEND rfrecon_default_dot_spacings ${s})
endforeach()
rfrecon_param_cache(RFRECON_DOT_SPACINGS "${rfrecon_default_dot_spacings}"
                    "Dot-grid spacings s the kernels support, an ascending ;-list (default 2 to 64, what the host \
accepts)")
set(RFRECON_KERNEL_PARAMS_BOARD "${RFRECON_FPGA_BOARD}" CACHE INTERNAL "the board whose preset the parameters follow")
set(rfrecon_kernel_params_template ${CMAKE_CURRENT_LIST_DIR}/../kernels/common/params.h.in)

function(rfrecon_configure_kernel_params out_dir)
  set(rfrecon_param_defines "")
  set(rfrecon_param_docs "")
  set(json_fields "")
  foreach(name IN LISTS rfrecon_kernel_param_names)
    list(GET rfrecon_kernel_param_${name}_range 0 min)
    list(GET rfrecon_kernel_param_${name}_range 1 max)
    set(value "${RFRECON_${name}}")
    if(NOT value MATCHES "^[0-9]+$" OR value LESS min OR value GREATER max)
      message(FATAL_ERROR "RFRECON_${name}=${value}: expected an integer from ${min} to ${max}")
    endif()
    if(rfrecon_kernel_param_${name}_kind STREQUAL "OVERRIDABLE")
      string(APPEND rfrecon_param_defines "#ifndef RF_${name}\n#define RF_${name} ${value}\n#endif\n")
    else()
      string(APPEND rfrecon_param_defines "#define RF_${name} ${value}\n")
    endif()
    list(APPEND json_fields "\"RF_${name}\": ${value}")
    string(APPEND rfrecon_param_docs "//   RF_${name}: ${rfrecon_kernel_param_${name}_help}; RFRECON_${name}, "
           "from ${min} to ${max}.\n")
  endforeach()

  if(RFRECON_DOT_SPACINGS STREQUAL "")
    message(FATAL_ERROR "RFRECON_DOT_SPACINGS is empty: name at least one dot spacing")
  endif()
  set(previous 1)
  foreach(s IN LISTS RFRECON_DOT_SPACINGS)
    if(NOT s MATCHES "^[0-9]+$" OR s LESS_EQUAL previous OR s GREATER 64)
      message(FATAL_ERROR "RFRECON_DOT_SPACINGS=${RFRECON_DOT_SPACINGS}: expected ascending integers from 2 to 64")
    endif()
    set(previous ${s})
  endforeach()
  list(JOIN RFRECON_DOT_SPACINGS ", " rfrecon_dot_spacings_c)
  list(LENGTH RFRECON_DOT_SPACINGS rfrecon_dot_spacing_count)
  set(rfrecon_max_dot_spacing ${previous})
  list(APPEND json_fields "\"RF_DOT_SPACINGS\": [${rfrecon_dot_spacings_c}]")

  math(EXPR last_frame "${RFRECON_FRAME_BATCH} - 1")
  set(rfrecon_each_frame "")
  foreach(f RANGE ${last_frame})
    list(APPEND rfrecon_each_frame "X(${f})")
  endforeach()
  list(JOIN rfrecon_each_frame ", " rfrecon_each_frame)

  list(JOIN json_fields ", " rfrecon_params_json)
  set(rfrecon_params_json "{${rfrecon_params_json}}")
  string(REPLACE "\"" "\\\"" rfrecon_params_json_c "${rfrecon_params_json}")
  configure_file(${rfrecon_kernel_params_template} ${out_dir}/kernels/common/params.h @ONLY)
  file(CONFIGURE OUTPUT ${out_dir}/kernels/common/params.json CONTENT "${rfrecon_params_json}\n")
endfunction()
