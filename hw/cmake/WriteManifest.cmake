# Script mode helper of the hw/ flows: writes BINARY.json, the manifest of a built FPGA binary (docs/formats.md): board,
# tool and version, target, the -D target macro, the parameters (GENERATED_DIR/common/params.json, written with the
# parameters header by cmake/EmbedKernelsParams.cmake), kernel names, and the SHA-256 of the kernel sources as
# cmake/EmbedKernelsSources.cmake computes it for the host (SOURCES relative to KERNEL_DIR, the generated parameters
# header in GENERATED_DIR), the SHA-256 of the binary itself, and the extra compiler flags (EXTRA_FLAGS_FILE, one per
# line). KERNELS and SOURCES come comma-separated.
include(${CMAKE_CURRENT_LIST_DIR}/../../cmake/EmbedKernelsSources.cmake)
if(NOT EXISTS ${BINARY})
  message(FATAL_ERROR "${BINARY} was not written by ${TOOL}")
endif()
string(REPLACE "," ";" KERNELS "${KERNELS}")
string(REPLACE "," ";" SOURCES "${SOURCES}")
rfrecon_kernel_source_sha256(source_hash ${KERNEL_DIR} ${GENERATED_DIR} ${SOURCES})

function(json_string var value)
  string(REPLACE "\\" "\\\\" value "${value}")
  string(REPLACE "\"" "\\\"" value "${value}")
  set(${var} "\"${value}\"" PARENT_SCOPE)
endfunction()
function(json_list var)
  set(items "")
  foreach(item IN LISTS ARGN)
    json_string(quoted "${item}")
    list(APPEND items "${quoted}")
  endforeach()
  list(JOIN items ", " joined)
  set(${var} "[${joined}]" PARENT_SCOPE)
endfunction()

get_filename_component(binary_name ${BINARY} NAME)
file(SHA256 ${BINARY} binary_hash)
file(STRINGS ${EXTRA_FLAGS_FILE} extra_flags)
set(fields "")
foreach(pair IN ITEMS "binary;${binary_name}" "board;${BOARD}" "device;${DEVICE}" "target;${TARGET}"
                      "tool;${TOOL}" "tool_version;${TOOL_VERSION}" "target_macro;${MACRO}"
                      "source_sha256;${source_hash}" "binary_sha256;${binary_hash}")
  list(GET pair 0 key)
  list(GET pair 1 value)
  json_string(quoted "${value}")
  list(APPEND fields "  \"${key}\": ${quoted}")
endforeach()
list(APPEND fields "  \"stand_in\": ${STAND_IN}")
file(READ ${GENERATED_DIR}/common/params.json parameters)
string(STRIP "${parameters}" parameters)
list(APPEND fields "  \"parameters\": ${parameters}")
json_list(extra_flags ${extra_flags})
list(APPEND fields "  \"extra_flags\": ${extra_flags}")
json_list(kernels ${KERNELS})
list(APPEND fields "  \"kernels\": ${kernels}")
json_list(sources ${SOURCES})
list(APPEND fields "  \"sources\": ${sources}")
list(JOIN fields ",\n" body)
file(WRITE ${BINARY}.json "{\n${body}\n}\n")
