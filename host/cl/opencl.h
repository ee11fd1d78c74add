// The one place that includes the Khronos OpenCL C++ bindings, so every file sees the same configuration.
#pragma once

#ifndef CL_HPP_TARGET_OPENCL_VERSION
#define CL_HPP_TARGET_OPENCL_VERSION 120
#endif
#ifndef CL_HPP_MINIMUM_OPENCL_VERSION
#define CL_HPP_MINIMUM_OPENCL_VERSION 120
#endif
#if defined(__GNUC__)
#pragma GCC system_header
#endif
#include <CL/opencl.hpp>
