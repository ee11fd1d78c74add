// Program building: cache hits, build logs on failure, and the binary path FPGA boards use, round-tripped on PoCL.
#include "host/cl/program_cache.h"

#include <filesystem>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "host/cl/device_selection.h"
#include "host/cl/error.h"
#include "host/cl/kernel_launch.h"
#include "host/selfcheck/axpy.h"
#include "tests/common/temp_dir.h"

namespace rfrecon::cl {
namespace {

using ::testing::EndsWith;
using ::testing::HasSubstr;
using ::testing::Not;

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

TEST(ProgramCacheTest, PreambleNamesOnlyFpgaTargets) {
  DeviceInfo info;
  EXPECT_THAT(device_preamble(info), Not(HasSubstr("#define"))) << "CPUs and GPUs get no target macro";
  EXPECT_THAT(device_preamble(info), EndsWith("#line 1\n"));
  info.intel_fpga = true;
  EXPECT_THAT(device_preamble(info), HasSubstr("#define RF_TARGET_INTEL_FPGA 1\n"));
  info.intel_fpga = false;
  info.xilinx_fpga = true;
  EXPECT_THAT(device_preamble(info), HasSubstr("#define RF_TARGET_XILINX_FPGA 1\n"));
}

TEST(ProgramCacheTest, BinaryRoundTripRunsTheSameKernel) {
  auto device = first_device();
  ProgramCache source_programs;
  const auto built = source_programs.get(device, "selfcheck/axpy.cl");
  const rfrecon::testing::TempDir temp("program_binary");
  const auto dir = temp.path();
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
  const ::cl::Buffer xb = upload(device.context(), x);
  const ::cl::Buffer yb = upload(device.context(), y, CL_MEM_READ_WRITE);
  set_args(kernel, 2.0f, xb, yb, static_cast<cl_uint>(x.size()));
  enqueue_kernel(device.queue(), kernel, KernelEntry::kNdRange, x.size());
  EXPECT_EQ(download<float>(device.queue(), yb, y.size()), selfcheck::axpy_reference(2.0f, x, y));
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
