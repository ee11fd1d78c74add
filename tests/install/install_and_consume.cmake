# Script mode (cmake -P) of the install_consumer test: `cmake --install` into PREFIX, check that the installed headers
# and package files stand alone, then configure, build and run the consumer project against PREFIX.
foreach(var BUILD_DIR PREFIX CONSUMER_SOURCE_DIR CONSUMER_BINARY_DIR WORK_DIR PROJECT_SOURCE_DIR GENERATOR
            CXX_COMPILER)
  if(NOT DEFINED ${var})
    message(FATAL_ERROR "install_and_consume.cmake: -D${var}=... missing")
  endif()
endforeach()

set(config_args "")
if(CONFIG)
  set(config_args --config ${CONFIG})
endif()

# A fresh prefix and consumer build, so that nothing left from an earlier run can hide a missing file.
file(REMOVE_RECURSE ${PREFIX} ${CONSUMER_BINARY_DIR})
execute_process(COMMAND ${CMAKE_COMMAND} --install ${BUILD_DIR} ${config_args} --prefix ${PREFIX}
                OUTPUT_QUIET COMMAND_ERROR_IS_FATAL ANY)

# Every installed header's quoted includes resolve inside the installed tree: from include/rfrecon ("host/...",
# "calib/...", "kernels/depth/...") or include/rfrecon/kernels ("depth/reciprocity.h"), as the targets' include
# directories say; a header of tests/, of the CLI or a generated one would be missing here.
set(include_root ${PREFIX}/include/rfrecon)
file(GLOB_RECURSE headers ${include_root}/*)
list(LENGTH headers header_count)
if(header_count EQUAL 0)
  message(FATAL_ERROR "no headers installed under ${include_root}")
endif()
set(unresolved "")
foreach(header IN LISTS headers)
  if(NOT header MATCHES "\\.h$")
    message(FATAL_ERROR "installed a file that is not a header: ${header}")
  endif()
  file(STRINGS ${header} includes REGEX "^[ \t]*#[ \t]*include[ \t]*\"")
  foreach(line IN LISTS includes)
    string(REGEX REPLACE "^[^\"]*\"([^\"]+)\".*$" "\\1" included "${line}")
    if(NOT EXISTS ${include_root}/${included} AND NOT EXISTS ${include_root}/kernels/${included})
      list(APPEND unresolved "${header}: ${included}")
    endif()
  endforeach()
endforeach()
if(unresolved)
  list(JOIN unresolved "\n  " unresolved)
  message(FATAL_ERROR "installed headers include files that are not installed:\n  ${unresolved}")
endif()

# The package files name installed paths only (relative to the prefix), never the source or build tree.
file(GLOB package_files ${PREFIX}/lib*/cmake/rfrecon/*.cmake)
if(NOT package_files)
  message(FATAL_ERROR "no CMake package installed under ${PREFIX}/lib*/cmake/rfrecon")
endif()
foreach(package_file IN LISTS package_files)
  file(READ ${package_file} text)
  foreach(tree ${PROJECT_SOURCE_DIR} ${BUILD_DIR})
    string(FIND "${text}" "${tree}/" at)
    if(NOT at EQUAL -1)
      message(FATAL_ERROR "${package_file} names ${tree}")
    endif()
  endforeach()
endforeach()
message(STATUS "installed into ${PREFIX}: ${header_count} headers, all includes resolve")

# The consumer: same generator, compilers and build type as this build, no other flags.
set(generator_args -G ${GENERATOR})
if(MAKE_PROGRAM)
  list(APPEND generator_args -DCMAKE_MAKE_PROGRAM=${MAKE_PROGRAM})
endif()
if(C_COMPILER)
  list(APPEND generator_args -DCMAKE_C_COMPILER=${C_COMPILER})
endif()
execute_process(COMMAND ${CMAKE_COMMAND} -S ${CONSUMER_SOURCE_DIR} -B ${CONSUMER_BINARY_DIR} ${generator_args}
                        -DCMAKE_CXX_COMPILER=${CXX_COMPILER} -DCMAKE_BUILD_TYPE=${CONFIG}
                        -DCMAKE_PREFIX_PATH=${PREFIX} -DCMAKE_FIND_PACKAGE_NO_PACKAGE_REGISTRY=ON
                COMMAND_ERROR_IS_FATAL ANY)
execute_process(COMMAND ${CMAKE_COMMAND} --build ${CONSUMER_BINARY_DIR} ${config_args}
                COMMAND_ERROR_IS_FATAL ANY)
execute_process(COMMAND ${CONSUMER_BINARY_DIR}/rfrecon_consumer ${WORK_DIR} RESULT_VARIABLE result)
if(NOT result EQUAL 0)
  message(FATAL_ERROR "rfrecon_consumer failed (${result}); its files are in ${WORK_DIR}")
endif()
