# The kernels' compile-time parameters (K, the depth kernels' row interleaves, maximum row width, frame batch, dot spacings) as cache options, and
# rfrecon_configure_kernel_params(OUT_DIR), which writes OUT_DIR/kernels/common/params.h from
# kernels/common/params.h.in. The host build (cmake/EmbedKernels.cmake) and the hw/ flows both call it, so a board
# binary and the host that loads it agree on the values unless they were configured differently, which the binary's
# manifest then shows (docs/fpga.md).
set(RFRECON_K 8 CACHE STRING "K, entries per camera pixel: the kernels' and the host's default, fixed in FPGA binaries")
if(DEFINED RFRECON_ROW_INTERLEAVE)
  message(FATAL_ERROR "RFRECON_ROW_INTERLEAVE is gone: each depth kernel has its own interleave, "
                      "RFRECON_INTEGRATE_INTERLEAVE and RFRECON_FUSE_INTERLEAVE (docs/fpga.md); remove it from the cache "
                      "(cmake -U RFRECON_ROW_INTERLEAVE)")
endif()
set(RFRECON_INTEGRATE_INTERLEAVE 160 CACHE STRING
    "Rows the single work-item integration interleaves: the latency in clocks of one RK4 slope (docs/fpga.md)")
set(RFRECON_FUSE_INTERLEAVE 32 CACHE STRING
    "Rows the single work-item fusion interleaves: the latency in clocks of its forward sweep's step (docs/fpga.md)")
set(RFRECON_MAX_ROW_WIDTH 4096 CACHE STRING "Widest row (pixels) a kernel keeps on chip")
set(RFRECON_FRAME_BATCH 16 CACHE STRING "Dot-grid frames per compression launch (each pixel's ELL row on chip across them)")
set(rfrecon_default_dot_spacings "")
foreach(s RANGE 2 64)
  list(APPEND rfrecon_default_dot_spacings ${s})
endforeach()
set(RFRECON_DOT_SPACINGS "${rfrecon_default_dot_spacings}" CACHE STRING
    "Dot-grid spacings s the kernels support, an ascending ;-list (default 2 to 64, what the host accepts)")
set(rfrecon_kernel_params_template ${CMAKE_CURRENT_LIST_DIR}/../kernels/common/params.h.in)

# rfrecon_check_kernel_param(NAME MIN MAX): NAME's value is an integer in [MIN, MAX].
function(rfrecon_check_kernel_param name min max)
  if(NOT "${${name}}" MATCHES "^[0-9]+$" OR ${name} LESS ${min} OR ${name} GREATER ${max})
    message(FATAL_ERROR "${name}=${${name}}: expected an integer from ${min} to ${max}")
  endif()
endfunction()

function(rfrecon_configure_kernel_params out_dir)
  # The bounds are the host's: K as `rfrecon transport -k` allows, widths and spacings as its inputs may have.
  rfrecon_check_kernel_param(RFRECON_K 1 64)
  rfrecon_check_kernel_param(RFRECON_INTEGRATE_INTERLEAVE 1 1024)
  rfrecon_check_kernel_param(RFRECON_FUSE_INTERLEAVE 1 1024)
  rfrecon_check_kernel_param(RFRECON_MAX_ROW_WIDTH 1 16384)
  rfrecon_check_kernel_param(RFRECON_FRAME_BATCH 2 64)  # a Gray pair per batch at least
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
  math(EXPR last_frame "${RFRECON_FRAME_BATCH} - 1")
  set(rfrecon_each_frame "")
  foreach(f RANGE ${last_frame})
    list(APPEND rfrecon_each_frame "X(${f})")
  endforeach()
  list(JOIN rfrecon_each_frame ", " rfrecon_each_frame)
  configure_file(${rfrecon_kernel_params_template} ${out_dir}/kernels/common/params.h @ONLY)
endfunction()
