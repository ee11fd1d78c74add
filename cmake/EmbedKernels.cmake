# rfrecon_embed_kernels(TARGET DIR): compiles every kernels/**/*.cl and *.h file into TARGET as a string table,
# so programs build from the sources without the files at run time. The .cl files stay plain OpenCL C;
# `#include "common/target.h"` is resolved against the table when a program is built (host/cl/kernel_sources.h).
function(rfrecon_embed_kernels target dir)
  file(GLOB_RECURSE kernel_files CONFIGURE_DEPENDS RELATIVE ${dir} ${dir}/*.cl ${dir}/*.h)
  list(SORT kernel_files)
  set(out ${CMAKE_CURRENT_BINARY_DIR}/generated/rfrecon/embedded_kernels.cc)
  set(abs_files "")
  foreach(f IN LISTS kernel_files)
    list(APPEND abs_files ${dir}/${f})
  endforeach()
  add_custom_command(
    OUTPUT ${out}
    COMMAND ${CMAKE_COMMAND} -DKERNEL_DIR=${dir} "-DKERNEL_FILES=${kernel_files}" -DOUT=${out}
            -P ${CMAKE_CURRENT_FUNCTION_LIST_DIR}/EmbedKernelsScript.cmake
    DEPENDS ${abs_files} ${CMAKE_CURRENT_FUNCTION_LIST_DIR}/EmbedKernelsScript.cmake
    COMMENT "Embedding OpenCL kernel sources"
    VERBATIM)
  target_sources(${target} PRIVATE ${out})
endfunction()
