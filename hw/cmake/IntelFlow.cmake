# Intel FPGA SDK for OpenCL flow (aoc, SDK 19.x to 22.4): every .cl file into one binary per target.
#   rfrecon_fpga_emulator  aoc -march=emulator  -> rfrecon_<board>_emulator.aocx   (seconds to minutes)
#   rfrecon_fpga_report    aoc -rtl -report     -> rfrecon_<board>_report.aocr and its reports/ (minutes)
#   rfrecon_fpga_hardware  aoc (full synthesis) -> rfrecon_<board>.aocx             (hours)
find_program(RFRECON_AOC aoc DOC "Intel FPGA SDK for OpenCL offline compiler (or a stand-in)")
if(NOT RFRECON_AOC)
  message(STATUS "FPGA ${RFRECON_FPGA_BOARD}: aoc not found, no FPGA targets (set RFRECON_AOC or source the SDK)")
  return()
endif()
fpga_tool_version(${RFRECON_AOC} -version "Version ([0-9]+\\.[0-9]+(\\.[0-9]+)?)")
if(fpga_tool_version VERSION_LESS 19.0 OR fpga_tool_version VERSION_GREATER_EQUAL 22.5)
  message(FATAL_ERROR "aoc ${fpga_tool_version} (${RFRECON_AOC}): the flow supports the Intel FPGA SDK for OpenCL "
                      "19.x to 22.4, the last release")
endif()
set(fpga_tool_name aoc)
set(fpga_macro RF_TARGET_INTEL_FPGA)
message(STATUS "FPGA ${RFRECON_FPGA_BOARD} (${RFRECON_FPGA_DESCRIPTION}): aoc ${fpga_tool_version} "
               "-board=${fpga_device}${fpga_stand_in_note}")

set(aoc_common -board=${fpga_device} ${fpga_includes} -D${fpga_macro}
               ${RFRECON_FPGA_EXTRA_FLAGS})
foreach(target IN ITEMS emulator report hardware)
  if(target STREQUAL "emulator")
    set(flags -march=emulator)
    set(binary ${fpga_out}/rfrecon_${RFRECON_FPGA_BOARD}_emulator.aocx)
  elseif(target STREQUAL "report")
    set(flags -rtl -report)
    set(binary ${fpga_out}/rfrecon_${RFRECON_FPGA_BOARD}_report.aocr)
  else()
    set(flags "")
    set(binary ${fpga_out}/rfrecon_${RFRECON_FPGA_BOARD}.aocx)
  endif()
  fpga_manifest_command(manifest ${binary} ${target} "${fpga_kernels}")
  add_custom_command(OUTPUT ${binary} ${binary}.json
                     COMMAND ${RFRECON_AOC} ${flags} ${aoc_common} ${fpga_cl_paths} -o ${binary}
                     COMMAND ${manifest}
                     DEPENDS ${fpga_source_paths} WORKING_DIRECTORY ${fpga_out} VERBATIM
                     COMMENT "aoc ${target}: ${RFRECON_FPGA_BOARD}")
  add_custom_target(rfrecon_fpga_${target} DEPENDS ${binary} ${binary}.json)
endforeach()

# The emulator binary's runs (emulation.env; with a real aoc a test dependency, tests/fpga/CMakeLists.txt): the
# environment that shows the emulated board to the host (SDK 19.x; later SDKs ignore it) and raises the emulator's
# private memory, whose default refuses the depth kernels' on-chip rows with CL_OUT_OF_RESOURCES (Programming Guide
# 22.4, 8.8). CL_CONFIG_CPU_FORCE_PRIVATE_MEM_SIZE is twice the larger kernel's rows, in whole MB, as
# kernels/depth/row_buffers.h counts them (RF_INTEGRATE_PRIVATE_BYTES, RF_FUSE_PRIVATE_BYTES), evaluated here with this
# build's parameters, a 4-byte float and the header's numeric macros: 22 MB at the defaults.
file(READ ${fpga_kernel_dir}/depth/row_buffers.h row_buffers)
string(REPLACE "\\\n" " " row_buffers "${row_buffers}")
set(private_bytes 0)
foreach(kernel IN ITEMS INTEGRATE FUSE)
  if(NOT row_buffers MATCHES "#define RF_${kernel}_PRIVATE_BYTES ([^\n]*)")
    message(FATAL_ERROR "${fpga_kernel_dir}/depth/row_buffers.h defines no RF_${kernel}_PRIVATE_BYTES, from which "
                        "hw/cmake/IntelFlow.cmake sizes the emulator's private memory")
  endif()
  set(expression "${CMAKE_MATCH_1}")
  string(REPLACE "(size_t)" "" expression "${expression}")
  string(REPLACE "sizeof(float)" "4" expression "${expression}")
  string(REGEX MATCHALL "RF_[A-Z0-9_]+" names "${expression}")
  foreach(name IN LISTS names)
    string(REGEX REPLACE "^RF_" "RFRECON_" option ${name})
    if(DEFINED ${option})
      set(value ${${option}})
    elseif(row_buffers MATCHES "#define ${name} ([0-9]+)\n")
      set(value ${CMAKE_MATCH_1})
    else()
      message(FATAL_ERROR "RF_${kernel}_PRIVATE_BYTES (kernels/depth/row_buffers.h): ${name} is neither a parameter "
                          "nor a number of that header")
    endif()
    string(REGEX REPLACE "${name}([^A-Za-z0-9_]|$)" "${value}\\1" expression "${expression}")
  endforeach()
  math(EXPR bytes "${expression}")
  if(bytes GREATER private_bytes)
    set(private_bytes ${bytes})
  endif()
endforeach()
math(EXPR private_mb "2 * ((${private_bytes} + 1048575) / 1048576)")
fpga_emulation(rfrecon_fpga_emulator ${fpga_out}/rfrecon_${RFRECON_FPGA_BOARD}_emulator.aocx
               CL_CONTEXT_EMULATOR_DEVICE_INTELFPGA=1 CL_CONFIG_CPU_FORCE_PRIVATE_MEM_SIZE=${private_mb}MB)
