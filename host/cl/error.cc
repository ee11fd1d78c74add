// Implementation of the OpenCL error types and the status-code name table.
#include "host/cl/error.h"

#include <cstring>

namespace rfrecon::cl {

std::string error_name(cl_int code) {
  switch (code) {
#define RF_CASE(name) \
  case name:          \
    return #name;
    RF_CASE(CL_SUCCESS)
    RF_CASE(CL_DEVICE_NOT_FOUND)
    RF_CASE(CL_DEVICE_NOT_AVAILABLE)
    RF_CASE(CL_COMPILER_NOT_AVAILABLE)
    RF_CASE(CL_MEM_OBJECT_ALLOCATION_FAILURE)
    RF_CASE(CL_OUT_OF_RESOURCES)
    RF_CASE(CL_OUT_OF_HOST_MEMORY)
    RF_CASE(CL_PROFILING_INFO_NOT_AVAILABLE)
    RF_CASE(CL_MEM_COPY_OVERLAP)
    RF_CASE(CL_IMAGE_FORMAT_MISMATCH)
    RF_CASE(CL_IMAGE_FORMAT_NOT_SUPPORTED)
    RF_CASE(CL_BUILD_PROGRAM_FAILURE)
    RF_CASE(CL_MAP_FAILURE)
    RF_CASE(CL_MISALIGNED_SUB_BUFFER_OFFSET)
    RF_CASE(CL_EXEC_STATUS_ERROR_FOR_EVENTS_IN_WAIT_LIST)
    RF_CASE(CL_COMPILE_PROGRAM_FAILURE)
    RF_CASE(CL_LINKER_NOT_AVAILABLE)
    RF_CASE(CL_LINK_PROGRAM_FAILURE)
    RF_CASE(CL_DEVICE_PARTITION_FAILED)
    RF_CASE(CL_KERNEL_ARG_INFO_NOT_AVAILABLE)
    RF_CASE(CL_INVALID_VALUE)
    RF_CASE(CL_INVALID_DEVICE_TYPE)
    RF_CASE(CL_INVALID_PLATFORM)
    RF_CASE(CL_INVALID_DEVICE)
    RF_CASE(CL_INVALID_CONTEXT)
    RF_CASE(CL_INVALID_QUEUE_PROPERTIES)
    RF_CASE(CL_INVALID_COMMAND_QUEUE)
    RF_CASE(CL_INVALID_HOST_PTR)
    RF_CASE(CL_INVALID_MEM_OBJECT)
    RF_CASE(CL_INVALID_IMAGE_FORMAT_DESCRIPTOR)
    RF_CASE(CL_INVALID_IMAGE_SIZE)
    RF_CASE(CL_INVALID_SAMPLER)
    RF_CASE(CL_INVALID_BINARY)
    RF_CASE(CL_INVALID_BUILD_OPTIONS)
    RF_CASE(CL_INVALID_PROGRAM)
    RF_CASE(CL_INVALID_PROGRAM_EXECUTABLE)
    RF_CASE(CL_INVALID_KERNEL_NAME)
    RF_CASE(CL_INVALID_KERNEL_DEFINITION)
    RF_CASE(CL_INVALID_KERNEL)
    RF_CASE(CL_INVALID_ARG_INDEX)
    RF_CASE(CL_INVALID_ARG_VALUE)
    RF_CASE(CL_INVALID_ARG_SIZE)
    RF_CASE(CL_INVALID_KERNEL_ARGS)
    RF_CASE(CL_INVALID_WORK_DIMENSION)
    RF_CASE(CL_INVALID_WORK_GROUP_SIZE)
    RF_CASE(CL_INVALID_WORK_ITEM_SIZE)
    RF_CASE(CL_INVALID_GLOBAL_OFFSET)
    RF_CASE(CL_INVALID_EVENT_WAIT_LIST)
    RF_CASE(CL_INVALID_EVENT)
    RF_CASE(CL_INVALID_OPERATION)
    RF_CASE(CL_INVALID_GL_OBJECT)
    RF_CASE(CL_INVALID_BUFFER_SIZE)
    RF_CASE(CL_INVALID_MIP_LEVEL)
    RF_CASE(CL_INVALID_GLOBAL_WORK_SIZE)
    RF_CASE(CL_INVALID_PROPERTY)
    RF_CASE(CL_INVALID_IMAGE_DESCRIPTOR)
    RF_CASE(CL_INVALID_COMPILER_OPTIONS)
    RF_CASE(CL_INVALID_LINKER_OPTIONS)
    RF_CASE(CL_INVALID_DEVICE_PARTITION_COUNT)
#undef RF_CASE
    case -1001:
      return "CL_PLATFORM_NOT_FOUND_KHR";
    default:
      return "CL_UNKNOWN_ERROR(" + std::to_string(code) + ")";
  }
}

namespace {
std::string describe(const std::string& call, cl_int code, const std::string& file, int line,
                     const std::string& detail) {
  std::string text =
      call + " failed: " + error_name(code) + " (" + std::to_string(code) + ") at " + file + ":" + std::to_string(line);
  if (!detail.empty()) text += "\n" + detail;
  return text;
}
}  // namespace

ClError::ClError(std::string call, cl_int code, std::string file, int line, const std::string& detail)
    : std::runtime_error(describe(call, code, file, line, detail)),
      call_(std::move(call)),
      code_(code),
      file_(std::move(file)),
      line_(line) {}

BuildError::BuildError(const std::string& program, const std::string& device, cl_int code, std::string log,
                       std::string file, int line)
    : ClError("clBuildProgram(" + program + ") on " + device, code, std::move(file), line, "build log:\n" + log),
      log_(std::move(log)) {}

void check(cl_int code, const char* call, const char* file, int line) {
  if (code != CL_SUCCESS) throw ClError(call, code, file, line);
}

}  // namespace rfrecon::cl
