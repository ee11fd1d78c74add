# AMD Vitis flow (v++): Vitis 2019.2 to 2022.2 compile the OpenCL C kernels; 2023.1 and later compile only C++ (HLS)
# and RTL kernels, so from 2023.1 the flow compiles the HLS C++ tops of hw/hls/ instead, which carry the single
# work-item entries' names, arguments and bodies (the same xclbin for the host either way). Each single work-item
# entry is compiled on its own, then all are linked into one .xclbin with the board's link configuration (compute units
# and memory banks). The HLS tops compile for hw_emu and hw as RFRECON_VITIS_HLS_MODE says (below): `v++ -c -k`, or
# `v++ -c --mode hls --config` (Vitis 2024.2 and later by default), and for sw_emu always with `v++ -c -k`.
#   rfrecon_fpga_sw_emu  -> rfrecon_<board>_sw_emu.xclbin and emconfig.json   (minutes)
#   rfrecon_fpga_hw_emu  -> rfrecon_<board>_hw_emu.xclbin and emconfig.json   (tens of minutes)
#   rfrecon_fpga_report  the hardware .xo files only: HLS synthesis and its reports under _x.hw/ (_x.hls/ with
#                        v++ --mode hls) (tens of minutes)
#   rfrecon_fpga_hw      -> rfrecon_<board>.xclbin                             (hours)
find_program(RFRECON_VXX v++ DOC "AMD Vitis compiler (or a stand-in)")
find_program(RFRECON_EMCONFIGUTIL emconfigutil DOC "AMD Vitis emulation configuration tool (or a stand-in)")
if(NOT RFRECON_VXX)
  message(STATUS "FPGA ${RFRECON_FPGA_BOARD}: v++ not found, no FPGA targets (set RFRECON_VXX or source Vitis)")
  return()
endif()
fpga_tool_version(${RFRECON_VXX} --version "v\\+\\+ v([0-9]+\\.[0-9]+(\\.[0-9]+)?)")
if(fpga_tool_version VERSION_LESS 2019.2)
  message(FATAL_ERROR "v++ ${fpga_tool_version} (${RFRECON_VXX}): the flow supports Vitis 2019.2 and later")
endif()
set(fpga_tool_name v++)
if(fpga_tool_version VERSION_LESS 2023.1)
  set(fpga_macro RF_TARGET_XILINX_FPGA)
  set(fpga_kernel_kind "OpenCL C kernels")
  message(WARNING "v++ ${fpga_tool_version} compiles the OpenCL C kernels, which bind no array to URAM (RF_IN_URAM): "
                  "the depth kernels' rows then need more block RAM than ${RFRECON_FPGA_BOARD}'s SLRs have, by the "
                  "budget (scripts/fpga_budget.py, docs/fpga.md#resource-budget). Vitis 2023.1 or later compiles "
                  "the HLS C++ tops, which do.")
  set(vxx_source_flags -D${fpga_macro})
else()
  set(fpga_macro RF_TARGET_HLS)  # defined by each top itself
  set(fpga_kernel_kind "HLS C++ tops of hw/hls/")
  set(vxx_source_flags -I ${CMAKE_CURRENT_SOURCE_DIR})  # the tops include "hls/..."
  # The top of each single work-item entry: the hw/hls/*.cpp file that defines extern "C" void <entry>(.
  file(GLOB fpga_hls_tops ${CMAKE_CURRENT_SOURCE_DIR}/hls/*.cpp)
  file(GLOB fpga_hls_headers ${CMAKE_CURRENT_SOURCE_DIR}/hls/*.h)
  foreach(top IN LISTS fpga_hls_tops)
    file(READ ${top} text)
    string(REGEX MATCHALL "extern \"C\" void [A-Za-z0-9_]+\\(" defined "${text}")
    foreach(definition IN LISTS defined)
      string(REGEX REPLACE "extern \"C\" void ([A-Za-z0-9_]+)\\(" "\\1" name "${definition}")
      set(fpga_hls_top_of_${name} ${top})
    endforeach()
  endforeach()
  # The manifests' sources, and so their source_sha256, include the tops (cmake/EmbedKernelsSources.cmake).
  rfrecon_hls_files(fpga_hls_sources ${fpga_kernel_dir})
  list(APPEND fpga_sources ${fpga_hls_sources})
endif()

# How v++ compiles the HLS C++ tops for hw_emu and hw (and so the report): `kernel`, the classic `v++ -c -t TARGET -k
# ENTRY FILE.cpp` (UG1393 2023.1; UG1702 2024.2 calls it still supported); `hls`, `v++ -c --mode hls --config
# ENTRY.cfg` with the [hls] section this flow generates (syn.file, syn.top, syn.cflags, flow_target=vitis, the
# platform, the .xo), the form UG1700 2025.2 shows, whose .xo serves hw_emu and hw alike; `auto`, hls from Vitis 2024.2.
# Software emulation compiles with -k in both, the form it needs (UG1393 2023.2, "Software Emulation Build").
set(RFRECON_VITIS_HLS_MODE auto CACHE STRING "v++ compile of the HLS C++ tops for hw_emu and hw: auto, kernel or hls")
set_property(CACHE RFRECON_VITIS_HLS_MODE PROPERTY STRINGS auto kernel hls)
set(vxx_hls_mode ${RFRECON_VITIS_HLS_MODE})
if(NOT vxx_hls_mode MATCHES "^(auto|kernel|hls)$")
  message(FATAL_ERROR "RFRECON_VITIS_HLS_MODE=${vxx_hls_mode}: expected auto, kernel or hls")
elseif(NOT fpga_macro STREQUAL "RF_TARGET_HLS")
  if(vxx_hls_mode STREQUAL "hls")
    message(FATAL_ERROR "RFRECON_VITIS_HLS_MODE=hls: v++ ${fpga_tool_version} (${RFRECON_VXX}) compiles the OpenCL C "
                        "kernels; v++ --mode hls and the HLS C++ tops need Vitis 2023.1 or later")
  endif()
  set(vxx_hls_mode "")
elseif(vxx_hls_mode STREQUAL "auto")
  if(fpga_tool_version VERSION_LESS 2024.2)
    set(vxx_hls_mode kernel)
  else()
    set(vxx_hls_mode hls)
  endif()
endif()
if(vxx_hls_mode STREQUAL "hls")
  string(APPEND fpga_kernel_kind " (hw_emu, hw: v++ -c --mode hls)")
elseif(vxx_hls_mode STREQUAL "kernel")
  string(APPEND fpga_kernel_kind " (v++ -c -k)")
endif()
message(STATUS "FPGA ${RFRECON_FPGA_BOARD} (${RFRECON_FPGA_DESCRIPTION}): v++ ${fpga_tool_version} "
               "--platform ${fpga_device}, ${fpga_kernel_kind}${fpga_stand_in_note}")

set(vxx_common --platform ${fpga_device} ${fpga_includes} ${vxx_source_flags} ${RFRECON_FPGA_EXTRA_FLAGS})
set(single_names "")
foreach(entry IN LISTS fpga_single_kernels)
  string(REGEX REPLACE ":.*" "" file ${entry})
  string(REGEX REPLACE ".*:" "" kernel ${entry})
  list(APPEND single_names ${kernel})
  set(source ${fpga_kernel_dir}/${file})
  set(depends ${fpga_source_paths})
  if(fpga_macro STREQUAL "RF_TARGET_HLS")
    if(NOT fpga_hls_top_of_${kernel})
      message(FATAL_ERROR "${kernel} (kernels/${file}) has no HLS C++ top in hw/hls/, which Vitis "
                          "${fpga_tool_version} needs: add one (docs/fpga.md)")
    endif()
    set(source ${fpga_hls_top_of_${kernel}})
    list(APPEND depends ${fpga_hls_tops} ${fpga_hls_headers})
  endif()
  set(kernel_targets sw_emu hw_emu hw)
  if(vxx_hls_mode STREQUAL "hls")
    # One .xo of HLS synthesis for hw_emu and hw, from a generated config: platform, then the [hls] section.
    set(kernel_targets sw_emu)
    set(xo ${fpga_out}/xo.hls/${kernel}.xo)
    set(config ${fpga_out}/hls_config/${kernel}.cfg)
    string(JOIN " " cflags -I${fpga_kernel_dir} -I${fpga_generated_dir} -I${CMAKE_CURRENT_SOURCE_DIR})
    file(CONFIGURE OUTPUT ${config} CONTENT "\
# v++ -c --mode hls configuration of ${kernel}, written by hw/cmake/XilinxFlow.cmake
platform=${fpga_device}

[hls]
flow_target=vitis
syn.file=${source}
syn.top=${kernel}
syn.cflags=${cflags}
package.output.format=xo
package.output.file=${xo}
")
    add_custom_command(OUTPUT ${xo}
                       COMMAND ${RFRECON_VXX} -c --mode hls --config ${config} --work_dir ${fpga_out}/_x.hls/${kernel}
                               ${RFRECON_FPGA_EXTRA_FLAGS}
                       DEPENDS ${depends} ${config} WORKING_DIRECTORY ${fpga_out} VERBATIM
                       COMMENT "v++ -c --mode hls: ${kernel}")
    list(APPEND xo_hw_emu ${xo})
    list(APPEND xo_hw ${xo})
  endif()
  foreach(target IN LISTS kernel_targets)
    set(xo ${fpga_out}/xo.${target}/${kernel}.xo)
    add_custom_command(OUTPUT ${xo}
                       COMMAND ${RFRECON_VXX} -c -t ${target} ${vxx_common} -k ${kernel} --temp_dir
                               ${fpga_out}/_x.${target}/${kernel} -o ${xo} ${source}
                       DEPENDS ${depends} WORKING_DIRECTORY ${fpga_out} VERBATIM
                       COMMENT "v++ -c ${target}: ${kernel}")
    list(APPEND xo_${target} ${xo})
  endforeach()
endforeach()
add_custom_target(rfrecon_fpga_report DEPENDS ${xo_hw})
# Emulation runs need the platform's emconfig.json beside the binary (XCL_EMULATION_MODE=sw_emu or hw_emu).
set(emconfig "")
if(RFRECON_EMCONFIGUTIL)
  set(emconfig ${fpga_out}/emconfig.json)
  add_custom_command(OUTPUT ${emconfig} COMMAND ${RFRECON_EMCONFIGUTIL} --platform ${fpga_device} --od ${fpga_out}
                     WORKING_DIRECTORY ${fpga_out} VERBATIM COMMENT "emconfigutil ${fpga_device}")
endif()

foreach(target IN ITEMS sw_emu hw_emu hw)
  if(target STREQUAL "hw")
    set(binary ${fpga_out}/rfrecon_${RFRECON_FPGA_BOARD}.xclbin)
  else()
    set(binary ${fpga_out}/rfrecon_${RFRECON_FPGA_BOARD}_${target}.xclbin)
  endif()
  fpga_manifest_command(manifest ${binary} ${target} "${single_names}")
  add_custom_command(OUTPUT ${binary} ${binary}.json
                     COMMAND ${RFRECON_VXX} -l -t ${target} --platform ${fpga_device} --config
                             ${RFRECON_FPGA_LINK_CONFIG} --temp_dir ${fpga_out}/_x.${target}/link -o ${binary}
                             ${xo_${target}}
                     COMMAND ${manifest}
                     DEPENDS ${xo_${target}} ${RFRECON_FPGA_LINK_CONFIG} WORKING_DIRECTORY ${fpga_out} VERBATIM
                     COMMENT "v++ -l ${target}: ${RFRECON_FPGA_BOARD}")
  set(outputs ${binary} ${binary}.json)
  if(NOT target STREQUAL "hw")
    list(APPEND outputs ${emconfig})
  endif()
  add_custom_target(rfrecon_fpga_${target} DEPENDS ${outputs})
endforeach()

# The software emulation binary's runs (emulation.env; with a real v++ a test dependency, tests/fpga/CMakeLists.txt):
# the environment XRT needs to run it.
fpga_emulation(rfrecon_fpga_sw_emu ${fpga_out}/rfrecon_${RFRECON_FPGA_BOARD}_sw_emu.xclbin XCL_EMULATION_MODE=sw_emu
               EMCONFIG_PATH=${fpga_out})
