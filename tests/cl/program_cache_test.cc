// Program building: cache hits, build logs on failure, and the binary path FPGA boards use, round-tripped on PoCL.
#include "host/cl/program_cache.h"

#include <filesystem>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "host/cl/device_selection.h"
#include "host/cl/error.h"
#include "host/selfcheck/axpy.h"

namespace rfrecon::cl {
namespace {

using ::testing::HasSubstr;

DeviceContext first_device() {
  const auto selected = select_devices(enumerate_devices(), effective_selection(""));
  return DeviceContext(selected.front());
}

TEST(ProgramCacheTest, SameSourceIsBuiltOnce) {
  auto device = first_device();
  ProgramCache programs;
  const auto a = programs.get(device, "selfcheck/axpy.cl");
  const auto b = programs.get(device, "selfcheck/axpy.cl");
  EXPECT_EQ(a(), b());
  EXPECT_EQ(programs.size(), 1U);
  (void)programs.get(device, "selfcheck/axpy.cl", "-cl-fast-relaxed-math");
  EXPECT_EQ(programs.size(), 2U) << "build options are part of the cache key";
}

// The *ApiErrorTest suites provoke OpenCL errors on purpose; CI's oclgrind pass skips them.
TEST(ProgramCacheApiErrorTest, CompileErrorCarriesBuildLog) {
  auto device = first_device();
  ProgramCache programs;
  try {
    (void)programs.build_source(device, "broken.cl", "__kernel void broken(__global float* x) { x[0] = y; }\n");
    FAIL() << "expected BuildError";
  } catch (const BuildError& error) {
    EXPECT_EQ(error.code(), CL_BUILD_PROGRAM_FAILURE);
    EXPECT_THAT(error.build_log(), HasSubstr("y"));
    EXPECT_THAT(error.what(), HasSubstr("broken.cl"));
    EXPECT_THAT(error.what(), HasSubstr("build log"));
  }
}

TEST(ProgramCacheTest, PreambleDescribesTheDevice) {
  auto device = first_device();
  const std::string preamble = device_preamble(device.info());
  if (device.info().kind == DeviceKind::kCpu) {
    EXPECT_THAT(preamble, HasSubstr("#define RF_DEVICE_CPU 1"));
  }
  EXPECT_EQ(device.info().fp64, preamble.find("RF_HAS_FP64") != std::string::npos);
}

TEST(ProgramCacheTest, BinaryRoundTripRunsTheSameKernel) {
  auto device = first_device();
  ProgramCache source_programs;
  const auto built = source_programs.get(device, "selfcheck/axpy.cl");
  const auto dir = std::filesystem::temp_directory_path() / ("rfrecon_bin_" + std::to_string(::getpid()));
  const auto path = dir / binary_file_name("selfcheck/axpy.cl", device.info());
  save_program_binary(built, path);
  ASSERT_TRUE(std::filesystem::exists(path));

  ProgramCache binary_programs(dir);
  const auto loaded = binary_programs.build_binary(device, path);
  cl_int status = CL_SUCCESS;
  ::cl::Kernel kernel(loaded, "axpy_ndrange", &status);
  EXPECT_EQ(status, CL_SUCCESS) << "the kernel must exist in the program loaded from its binary";

  // The loaded program computes what the reference computes.
  const std::vector<float> x{1, 2, 3, 4};
  const std::vector<float> y{0.5f, -1, 2, 8};
  std::vector<float> out = y;
  const std::size_t bytes = x.size() * sizeof(float);
  const cl_mem_flags in_flags = CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR;
  const cl_mem_flags inout_flags = CL_MEM_READ_WRITE | CL_MEM_COPY_HOST_PTR;
  ::cl::Buffer xb(device.context(), in_flags, bytes, const_cast<float*>(x.data()));
  ::cl::Buffer yb(device.context(), inout_flags, bytes, out.data());
  kernel.setArg(0, 2.0f);
  kernel.setArg(1, xb);
  kernel.setArg(2, yb);
  kernel.setArg(3, cl_uint{4});
  RF_CL_CHECK(device.queue().enqueueNDRangeKernel(kernel, ::cl::NullRange, ::cl::NDRange(4)));
  RF_CL_CHECK(device.queue().enqueueReadBuffer(yb, CL_TRUE, 0, bytes, out.data()));
  EXPECT_EQ(out, selfcheck::axpy_reference(2.0f, x, y));
  std::filesystem::remove_all(dir);
}

TEST(ProgramCacheApiErrorTest, MissingBinaryIsNamed) {
  auto device = first_device();
  ProgramCache programs;
  try {
    (void)programs.build_binary(device, "/nonexistent/selfcheck_axpy.aocx");
    FAIL() << "expected an error";
  } catch (const std::runtime_error& error) {
    EXPECT_THAT(error.what(), HasSubstr("/nonexistent/selfcheck_axpy.aocx"));
  }
}

TEST(ProgramCacheTest, BinaryNamesFollowTheVendorFlow) {
  DeviceInfo info;
  info.intel_fpga = true;
  EXPECT_EQ(binary_file_name("transport/decode.cl", info), "transport_decode.aocx");
  info.intel_fpga = false;
  info.xilinx_fpga = true;
  EXPECT_EQ(binary_file_name("transport/decode.cl", info), "transport_decode.xclbin");
}

}  // namespace
}  // namespace rfrecon::cl
