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

# With a real aoc, the emulator binary is a test dependency (tests/fpga/CMakeLists.txt): its target, the binary, and
# the environment that shows the emulated board to the host (SDK 19.x; later SDKs ignore it) and raises the
# emulator's private memory to twice the depth kernels' on-chip rows (kernels/depth/row_buffers.h: 17 bytes per pixel
# of an integration row, 25 of a fusion row), which its default refuses with CL_OUT_OF_RESOURCES (Programming Guide
# 22.4, 8.8).
if(NOT fpga_stand_in)
  math(EXPR integrate_bytes "${RFRECON_INTEGRATE_INTERLEAVE} * ${RFRECON_MAX_ROW_WIDTH} * 17")
  math(EXPR fuse_bytes "${RFRECON_FUSE_INTERLEAVE} * ${RFRECON_MAX_ROW_WIDTH} * 25")
  if(fuse_bytes GREATER integrate_bytes)
    set(integrate_bytes ${fuse_bytes})
  endif()
  math(EXPR private_mb "2 * (${integrate_bytes} + 1048575) / 1048576")
  set_property(GLOBAL PROPERTY RFRECON_FPGA_EMULATION rfrecon_fpga_emulator
               ${fpga_out}/rfrecon_${RFRECON_FPGA_BOARD}_emulator.aocx CL_CONTEXT_EMULATOR_DEVICE_INTELFPGA=1
               CL_CONFIG_CPU_FORCE_PRIVATE_MEM_SIZE=${private_mb}MB)
endif()
