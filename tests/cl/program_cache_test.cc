// Program building: cache hits, the on-disk program store, build logs on failure, and the board binary path FPGA
// boards use, run on PoCL.
#include "host/cl/program_cache.h"

#include <filesystem>
#include <fstream>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "host/cl/device_selection.h"
#include "host/cl/error.h"
#include "host/cl/kernel_launch.h"
#include "host/cl/kernel_sources.h"
#include "host/core/file_sha256.h"
#include "host/selfcheck/axpy.h"
#include "kernels/common/params.h"
#include "tests/common/devices.h"
#include "tests/common/scoped_env.h"
#include "tests/common/temp_dir.h"

namespace rfrecon::cl {
namespace {

using ::testing::EndsWith;
using ::testing::HasSubstr;
using ::testing::Not;

using rfrecon::testing::first_device;
using rfrecon::testing::ScopedEnv;

// axpy from `program` computes what the C++ reference computes.
void expect_axpy_like_reference(DeviceContext& device, const ::cl::Program& program) {
  cl_int status = CL_SUCCESS;
  ::cl::Kernel kernel(program, "axpy_ndrange", &status);
  ASSERT_EQ(status, CL_SUCCESS) << "the program must hold the kernel";
  const std::vector<float> x{1, 2, 3, 4};
  const std::vector<float> y{0.5f, -1, 2, 8};
  const ::cl::Buffer xb = upload(device.context(), x);
  const ::cl::Buffer yb = upload(device.context(), y, CL_MEM_READ_WRITE);
  set_args(kernel, 2.0f, xb, yb, static_cast<cl_uint>(x.size()));
  enqueue_kernel(device.queue(), kernel, KernelEntry::kNdRange, x.size());
  EXPECT_EQ(download<float>(device.queue(), yb, y.size()), selfcheck::axpy_reference(2.0f, x, y));
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
  const auto path = dir / "selfcheck_axpy.bin";
  save_program_binary(built, path);
  ASSERT_TRUE(std::filesystem::exists(path));

  ProgramCache binary_programs(dir);
  expect_axpy_like_reference(device, binary_programs.build_binary(device, path));
}

// The program store (docs/performance.md#program-cache): a second cache on the same directory loads what the first
// compiled, without compiling, and the loaded program computes what the reference computes.
TEST(ProgramStoreTest, StoredProgramsLoadWithoutCompiling) {
  auto device = first_device();
  const rfrecon::testing::TempDir temp("program_store");
  ProgramCache first({}, ProgramStore(temp.path()));
  (void)first.get(device, "selfcheck/axpy.cl");
  EXPECT_EQ(first.builds().built, 1);
  EXPECT_EQ(first.builds().loaded, 0);
  ASSERT_EQ(std::distance(std::filesystem::directory_iterator(temp.path()), {}), 1) << "one stored binary";

  ProgramCache second({}, ProgramStore(temp.path()));
  expect_axpy_like_reference(device, second.get(device, "selfcheck/axpy.cl"));
  EXPECT_EQ(second.builds().built, 0);
  EXPECT_EQ(second.builds().loaded, 1);
  (void)second.get(device, "selfcheck/axpy.cl", "-cl-fast-relaxed-math");
  EXPECT_EQ(second.builds().built, 1) << "other build options are another stored program";
  EXPECT_EQ(ProgramStore(temp.path()).clear(), 2U);
  EXPECT_TRUE(std::filesystem::is_empty(temp.path()));
}

// An *ApiErrorTest: clCreateProgramWithBinary refuses the damaged file on purpose (CI's oclgrind pass skips it).
TEST(ProgramStoreApiErrorTest, AStoredBinaryThatDoesNotLoadIsCompiledAgainAndReplaced) {
  auto device = first_device();
  const rfrecon::testing::TempDir temp("program_store_bad");
  ProgramCache first({}, ProgramStore(temp.path()));
  (void)first.get(device, "selfcheck/axpy.cl");
  const auto stored = std::filesystem::directory_iterator(temp.path())->path();
  std::ofstream(stored, std::ios::binary | std::ios::trunc) << "not a program binary";

  ProgramCache second({}, ProgramStore(temp.path()));
  expect_axpy_like_reference(device, second.get(device, "selfcheck/axpy.cl"));
  EXPECT_EQ(second.builds().built, 1);
  EXPECT_EQ(second.builds().loaded, 0);
  ProgramCache third({}, ProgramStore(temp.path()));
  (void)third.get(device, "selfcheck/axpy.cl");
  EXPECT_EQ(third.builds().loaded, 1) << "the compiled program replaced the bad file";
}

TEST(ProgramStoreTest, DirectoryComesFromTheEnvironmentAndOffDisablesIt) {
  {
    const ScopedEnv chosen(kProgramCacheEnv, "/tmp/rfrecon-programs");
    EXPECT_EQ(ProgramStore::default_directory(), "/tmp/rfrecon-programs");
  }
  {
    const ScopedEnv off(kProgramCacheEnv, "off");
    EXPECT_FALSE(ProgramStore().enabled());
  }
  const ScopedEnv unset(kProgramCacheEnv, nullptr);
  const ScopedEnv xdg("XDG_CACHE_HOME", "/tmp/xdg");
  EXPECT_EQ(ProgramStore::default_directory(), "/tmp/xdg/rfrecon/programs");
  auto device = first_device();
  ProgramCache programs({}, ProgramStore(std::filesystem::path()));
  (void)programs.get(device, "selfcheck/axpy.cl");
  EXPECT_EQ(programs.builds().built, 1) << "a cache without a store still compiles";
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

// Every embedded .cl file in one program, as the hw/ flows put them into one board binary.
std::string every_kernel_source() {
  std::string text;
  for (const auto& file : embedded_kernel_files()) {
    if (file.path.size() > 3 && file.path.substr(file.path.size() - 3) == ".cl") {
      text += resolve_kernel_source(file.path);
    }
  }
  return text;
}

// A PoCL binary of every kernel, with a manifest that matches this host, loaded through the board path: the device
// is made to look like an FPGA board (no online compiler), so get() must serve every kernel file from that one
// binary, check the build options against it, and the loaded kernels must compute what the reference computes.
TEST(ProgramCacheTest, BoardBinaryServesEveryKernelFileFromOneLoad) {
  auto entry = select_devices(enumerate_devices(), effective_selection("")).front();
  DeviceContext compiler(entry);
  ProgramCache source_programs;
  const auto built = source_programs.build_source(compiler, "every kernel", every_kernel_source());
  const rfrecon::testing::TempDir temp("board_binary");
  const auto binary = temp.path() / "rfrecon_pocl.bin";
  save_program_binary(built, binary);
  entry.info.compiler_available = false;
  DeviceContext board(entry);
  const auto expected = host_manifest_expectation(board.info());
  const nlohmann::json manifest = {{"binary", binary.filename().string()},
                                   {"board", "pocl"},
                                   {"device", describe(board.info())},
                                   {"target", "test"},
                                   {"tool", "pocl"},
                                   {"tool_version", "0"},
                                   {"target_macro", expected.target_macros.front()},
                                   {"parameters", expected.parameters},
                                   {"kernels", embedded_kernel_names()},
                                   {"sources", nlohmann::json::array()},
                                   {"source_sha256", expected.source_sha256},
                                   {"binary_sha256", file_sha256(binary)},
                                   {"extra_flags", nlohmann::json::array()},
                                   {"stand_in", false}};
  std::ofstream(binary.string() + ".json") << manifest.dump(2);

  ProgramCache programs(temp.path());
  ASSERT_TRUE(programs.uses_binary(board.info()));
  const auto axpy = programs.get(board, "selfcheck/axpy.cl");
  EXPECT_EQ(programs.get(board, "transport/spmv.cl")(), axpy());
  EXPECT_EQ(programs.get(board, "transport/compress.cl", "-DRF_K=" + std::to_string(RF_K))(), axpy());
  EXPECT_EQ(programs.size(), 1U) << "one binary loaded once serves every kernel file";
  try {
    (void)programs.get(board, "transport/compress.cl", "-DRF_K=" + std::to_string(RF_K + 1));
    FAIL() << "a run-time K other than the binary's must be refused";
  } catch (const BinaryManifestError& error) {
    EXPECT_EQ(error.field(), "parameters.RF_K");
    EXPECT_THAT(error.what(), HasSubstr(binary.string() + ".json"));
  }

  for (const auto kernel_entry : {KernelEntry::kNdRange, KernelEntry::kSingleWorkItem}) {
    ::cl::Kernel kernel = make_kernel(axpy, "axpy", kernel_entry);
    const std::vector<float> x{1, 2, 3, 4};
    const std::vector<float> y{0.5f, -1, 2, 8};
    const ::cl::Buffer xb = upload(board.context(), x);
    const ::cl::Buffer yb = upload(board.context(), y, CL_MEM_READ_WRITE);
    set_args(kernel, 2.0f, xb, yb, static_cast<cl_uint>(x.size()));
    enqueue_kernel(board.queue(), kernel, kernel_entry, x.size());
    EXPECT_EQ(download<float>(board.queue(), yb, y.size()), selfcheck::axpy_reference(2.0f, x, y));
  }
}

}  // namespace
}  // namespace rfrecon::cl
