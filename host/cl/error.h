// OpenCL errors as exceptions that carry the failing call, the status code's name and the source location.
#pragma once

#include <stdexcept>
#include <string>

#include "host/cl/opencl.h"

namespace rfrecon::cl {

// Name of an OpenCL status code ("CL_OUT_OF_RESOURCES"); "CL_UNKNOWN_ERROR(<n>)" for codes it does not know.
std::string error_name(cl_int code);

// A failed OpenCL call. what() reads "clCreateBuffer failed: CL_INVALID_VALUE (-30) at host/x.cc:42".
class ClError : public std::runtime_error {
 public:
  ClError(std::string call, cl_int code, std::string file, int line, const std::string& detail = {});
  const std::string& call() const { return call_; }
  cl_int code() const { return code_; }
  const std::string& file() const { return file_; }
  int line() const { return line_; }

 private:
  std::string call_;
  cl_int code_;
  std::string file_;
  int line_;
};

// A program that failed to build; build_log() holds the compiler's output for the device.
class BuildError : public ClError {
 public:
  BuildError(const std::string& program, const std::string& device, cl_int code, std::string log, std::string file,
             int line);
  const std::string& build_log() const { return log_; }

 private:
  std::string log_;
};

// No device matched a selection (bad --devices value, empty platform list, ...).
class DeviceSelectionError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Throws ClError when code is not CL_SUCCESS.
void check(cl_int code, const char* call, const char* file, int line);

}  // namespace rfrecon::cl

// RF_CL_CHECK(clFinish(q)) or RF_CL_CHECK(queue.finish()): throws ClError naming the call on failure.
#define RF_CL_CHECK(expr) ::rfrecon::cl::check((expr), #expr, __FILE__, __LINE__)
// RF_CL_CHECK_CODE(err, "clCreateBuffer"): for calls that report through an out-parameter.
#define RF_CL_CHECK_CODE(code, call) ::rfrecon::cl::check((code), (call), __FILE__, __LINE__)
