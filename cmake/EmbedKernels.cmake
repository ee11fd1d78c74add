# rfrecon_embed_kernels(TARGET DIR): compiles every kernels/**/*.cl and *.h file, and the parameters header
# configured from DIR/common/params.h.in (cmake/EmbedKernelsParams.cmake), into TARGET as a string table, so programs
# build from the sources without the files at run time; also the SHA-256 of those sources and of those with the HLS
# C++ tops of hw/hls (as the hw/ flows' manifests record them) and the names of their kernels. The .cl files stay plain OpenCL C; `#include "common/target.h"` is
# resolved against the table when a program is built (host/cl/kernel_sources.h). The generated header lies under
# PROJECT_BINARY_DIR/generated/kernels, the include directory rfrecon_kernels adds for it.
include(${CMAKE_CURRENT_LIST_DIR}/EmbedKernelsParams.cmake)
include(${CMAKE_CURRENT_LIST_DIR}/EmbedKernelsSources.cmake)
set(RFRECON_GENERATED_KERNEL_DIR ${PROJECT_BINARY_DIR}/generated/kernels)
rfrecon_configure_kernel_params(${PROJECT_BINARY_DIR}/generated)

function(rfrecon_embed_kernels target dir)
  rfrecon_kernel_files(kernel_files ${dir})
  rfrecon_hls_files(hls_files ${dir})
  set(out ${CMAKE_CURRENT_BINARY_DIR}/generated/rfrecon/embedded_kernels.cc)
  set(abs_files "")
  foreach(f IN LISTS kernel_files hls_files)
    rfrecon_kernel_file_path(path ${f} ${dir} ${RFRECON_GENERATED_KERNEL_DIR})
    list(APPEND abs_files ${path})
  endforeach()
  add_custom_command(
    OUTPUT ${out}
    COMMAND ${CMAKE_COMMAND} -DKERNEL_DIR=${dir} -DGENERATED_DIR=${RFRECON_GENERATED_KERNEL_DIR}
            "-DKERNEL_FILES=${kernel_files}" "-DHLS_FILES=${hls_files}" -DOUT=${out} -P ${CMAKE_CURRENT_FUNCTION_LIST_DIR}/EmbedKernelsScript.cmake
    DEPENDS ${abs_files} ${CMAKE_CURRENT_FUNCTION_LIST_DIR}/EmbedKernelsScript.cmake
            ${CMAKE_CURRENT_FUNCTION_LIST_DIR}/EmbedKernelsSources.cmake
    COMMENT "Embedding OpenCL kernel sources"
    VERBATIM)
  target_sources(${target} PRIVATE ${out})
endfunction()
