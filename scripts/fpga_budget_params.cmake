# One board preset's kernel parameters, written as the hw/ flow writes them (hw/CMakeLists.txt: the preset, then the
# table of cmake/EmbedKernelsParams.cmake), in CMake script mode for scripts/fpga_budget.py:
#   cmake -DROOT=<source dir> -DBOARD_FILE=<hw/boards/NAME.cmake> -DOUT=<dir> [-DBUDGET_SET=NAME=VALUE;...]
#         -P fpga_budget_params.cmake
# writes OUT/kernels/common/params.h and OUT/preset.txt (the preset's variables the budget reads, NAME=VALUE lines).
# BUDGET_SET sets RFRECON_<NAME> after the preset, as -DRFRECON_<NAME>= would on a flow's command line.
cmake_policy(VERSION 3.25)
include(${BOARD_FILE})
foreach(assignment IN LISTS BUDGET_SET)
  string(REGEX MATCH "^([A-Z_]+)=(.*)$" matched "${assignment}")
  if(NOT matched)
    message(FATAL_ERROR "BUDGET_SET: expected NAME=VALUE, got ${assignment}")
  endif()
  set(RFRECON_${CMAKE_MATCH_1} "${CMAKE_MATCH_2}")
endforeach()
include(${ROOT}/cmake/EmbedKernelsParams.cmake)
rfrecon_configure_kernel_params(${OUT})
if(NOT DEFINED RFRECON_FPGA_SUPPORTED)
  set(RFRECON_FPGA_SUPPORTED ON)
endif()
file(WRITE ${OUT}/preset.txt "VENDOR=${RFRECON_FPGA_VENDOR}\nDESCRIPTION=${RFRECON_FPGA_DESCRIPTION}\n"
     "LINK_CONFIG=${RFRECON_FPGA_LINK_CONFIG}\nSUPPORTED=${RFRECON_FPGA_SUPPORTED}\n")
