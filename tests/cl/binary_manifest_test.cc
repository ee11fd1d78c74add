// The manifest checks the host makes before loading a board binary (ctest label fpga; no device, no vendor tool).
// The starting point is a real manifest: the Intel emulator flow of hw/ is run once with the stand-in aoc of
// tests/fpga, so the tests also show that the flow's source hash, parameters and kernel list are the host's.
#include "host/cl/binary_manifest.h"

#include <cstdlib>
#include <fstream>
#include <string>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "host/cl/kernel_sources.h"
#include "kernels/common/params.h"
#include "tests/common/scoped_env.h"
#include "tests/common/temp_dir.h"

namespace rfrecon::cl {
namespace {

using rfrecon::testing::ScopedEnv;
using ::testing::HasSubstr;

// A stand-in flow of hw/: the board, the stand-in tools as configure options, the environment of both steps, the
// target built and the binary it writes (beside it, its manifest).
struct StandInFlow {
  std::string board, tools, environment, target, binary;
};
// The configure options that give a flow this host's parameters in place of its preset's (hw/boards/: dot spacings,
// and rows and interleaves on some boards), as for a host configured without the board.
std::string host_parameter_options() {
  std::string spacings;
  for (const int s : std::vector<int> RF_DOT_SPACINGS) spacings += (spacings.empty() ? "" : ";") + std::to_string(s);
  return " -DRFRECON_MAX_ROW_WIDTH=" + std::to_string(RF_MAX_ROW_WIDTH) +
         " -DRFRECON_INTEGRATE_INTERLEAVE=" + std::to_string(RF_INTEGRATE_INTERLEAVE) +
         " -DRFRECON_FUSE_INTERLEAVE=" + std::to_string(RF_FUSE_INTERLEAVE) + " \"-DRFRECON_DOT_SPACINGS=" + spacings +
         "\"";
}
StandInFlow intel_emulator() {
  return {"520n",
          "-DRFRECON_AOC=\"" + std::string(RFRECON_SOURCE_DIR) + "/tests/fpga/bin/aoc\"" + host_parameter_options(), "",
          "rfrecon_fpga_emulator", "rfrecon_520n_emulator.aocx"};
}
// The u250 flow of the HLS C++ tops, as Vitis 2023.1 and later build them (v++ -c -k).
StandInFlow u250_hls_sw_emu() {
  const std::string bin = std::string(RFRECON_SOURCE_DIR) + "/tests/fpga/bin";
  return {"u250",
          "-DRFRECON_VXX=\"" + bin + "/v++\" -DRFRECON_EMCONFIGUTIL=\"" + bin + "/emconfigutil\"" +
              host_parameter_options(),
          "RFRECON_STANDIN_VERSION=2023.1 ", "rfrecon_fpga_sw_emu", "rfrecon_u250_sw_emu.xclbin"};
}
// The same flow's hardware emulation binary as Vitis 2025.1 builds it: each top by v++ -c --mode hls.
StandInFlow u250_hls_mode_hw_emu() {
  StandInFlow flow = u250_hls_sw_emu();
  flow.environment = "RFRECON_STANDIN_VERSION=2025.1 ";
  flow.target = "rfrecon_fpga_hw_emu";
  flow.binary = "rfrecon_u250_hw_emu.xclbin";
  return flow;
}

// Runs `flow` in `build` (with further configure options) and returns the manifest it wrote.
nlohmann::json run_flow(const std::filesystem::path& build, const std::string& options = {},
                        const StandInFlow& flow = intel_emulator()) {
  const std::string cmake = RFRECON_CMAKE_COMMAND;
  const std::string log = (build / "flow.log").string();
  const std::string configure = flow.environment + "\"" + cmake + "\" -S \"" + RFRECON_SOURCE_DIR + "/hw\" -B \"" +
                                build.string() + "\" -DRFRECON_FPGA_BOARD=" + flow.board + " " + flow.tools + " " +
                                options;
  const std::string compile =
      flow.environment + "\"" + cmake + "\" --build \"" + build.string() + "\" --target " + flow.target;
  if (std::system((configure + " > \"" + log + "\" 2>&1 && " + compile + " >> \"" + log + "\" 2>&1").c_str()) != 0) {
    ADD_FAILURE() << "the stand-in flow failed; see " << log;
    return nlohmann::json::object();
  }
  std::ifstream in(build / (flow.binary + ".json"));
  return nlohmann::json::parse(in);
}

class BinaryManifestTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    flow_ = new rfrecon::testing::TempDir("manifest_flow");
    flow_manifest_ = new nlohmann::json(run_flow(flow_->path()));
  }
  static void TearDownTestSuite() {
    delete flow_manifest_;
    delete flow_;
  }

  void SetUp() override {
    intel_.intel_fpga = true;
    intel_.compiler_available = false;
    intel_.fpga_emulation = "emulator";  // the device the flow's binary, an emulator one, is for
  }

  // Writes `manifest` beside a binary named after its `binary` field: a copy of the flow's (stand-in) binary, which
  // nothing loads here, so that binary_sha256 holds.
  std::filesystem::path write(const nlohmann::json& manifest, const std::string& text = {}) const {
    const auto binary = temp_.path() / manifest.value("binary", std::string("board.aocx"));
    std::filesystem::copy_file(flow_->path() / "rfrecon_520n_emulator.aocx", binary,
                               std::filesystem::copy_options::overwrite_existing);
    std::ofstream(binary.string() + ".json") << (text.empty() ? manifest.dump(2) : text);
    return binary;
  }

  // The flow's manifest as a real aoc would have written it: the same but for stand_in.
  static nlohmann::json real_manifest() {
    nlohmann::json manifest = *flow_manifest_;
    manifest["stand_in"] = false;
    return manifest;
  }

  // Expects check_binary_manifest to refuse for `device` (default: an Intel board), naming the manifest file and
  // `field`; returns the message.
  std::string refusal(const std::filesystem::path& binary, const std::string& field,
                      const DeviceInfo* device = nullptr) const {
    try {
      (void)check_binary_manifest(binary, host_manifest_expectation(device != nullptr ? *device : intel_));
    } catch (const BinaryManifestError& error) {
      EXPECT_EQ(error.field(), field) << error.what();
      EXPECT_EQ(error.code(), CL_INVALID_BINARY);
      EXPECT_THAT(error.what(), HasSubstr(error.manifest_file().string()));
      return error.what();
    }
    ADD_FAILURE() << binary << ": accepted, expected a refusal naming " << field;
    return {};
  }

  static rfrecon::testing::TempDir* flow_;
  static nlohmann::json* flow_manifest_;
  DeviceInfo intel_;
  rfrecon::testing::TempDir temp_{"manifest_case"};
};
rfrecon::testing::TempDir* BinaryManifestTest::flow_ = nullptr;
nlohmann::json* BinaryManifestTest::flow_manifest_ = nullptr;

// The parameter table writes both the header's macros and the JSON object the host expects in a manifest: they agree.
TEST(HostKernelParametersTest, AreTheHeadersMacros) {
  const nlohmann::json parameters = host_kernel_parameters();
  EXPECT_EQ(parameters.size(), 6u) << parameters.dump();
  EXPECT_EQ(parameters.at("RF_K"), RF_K);
  EXPECT_EQ(parameters.at("RF_INTEGRATE_INTERLEAVE"), RF_INTEGRATE_INTERLEAVE);
  EXPECT_EQ(parameters.at("RF_FUSE_INTERLEAVE"), RF_FUSE_INTERLEAVE);
  EXPECT_EQ(parameters.at("RF_MAX_ROW_WIDTH"), RF_MAX_ROW_WIDTH);
  EXPECT_EQ(parameters.at("RF_FRAME_BATCH"), RF_FRAME_BATCH);
  const std::vector<int> dot_spacings RF_DOT_SPACINGS;
  EXPECT_EQ(parameters.at("RF_DOT_SPACINGS").get<std::vector<int>>(), dot_spacings);
}

TEST_F(BinaryManifestTest, RealBinaryOfTheFlowIsAccepted) {
  const auto binary = write(real_manifest());
  const BinaryManifest checked = check_binary_manifest(binary, host_manifest_expectation(intel_));
  EXPECT_EQ(checked.file, binary.string() + ".json");
  EXPECT_EQ(checked.parameters.at("RF_K"), RF_K);
  EXPECT_EQ(checked.parameters.at("RF_DOT_SPACINGS").size(), static_cast<std::size_t>(RF_DOT_SPACING_COUNT));
  EXPECT_EQ(checked.parameters.at("RF_DOT_SPACINGS").back(), RF_MAX_DOT_SPACING);
}

// A binary rebuilt or replaced without its manifest: its bytes no longer hash to binary_sha256.
TEST_F(BinaryManifestTest, BinaryChangedSinceItsManifestIsRefused) {
  const auto binary = write(real_manifest());
  std::ofstream(binary, std::ios::app) << "rebuilt";
  EXPECT_THAT(refusal(binary, "binary_sha256"), HasSubstr("replaced without its manifest"));
}

// The flow records RFRECON_FPGA_EXTRA_FLAGS in the manifest, one string per flag, and the host reads them back (and
// logs them when it loads the binary, host/cl/program_cache.cc).
TEST_F(BinaryManifestTest, ExtraFlagsAreRecorded) {
  EXPECT_EQ(real_manifest().at("extra_flags"), nlohmann::json::array());
  rfrecon::testing::TempDir other("manifest_flow_flags");
  auto manifest = run_flow(other.path(), "\"-DRFRECON_FPGA_EXTRA_FLAGS=-DRF_TEST_A=1;-DRF_TEST_B=1,2\"");
  const nlohmann::json flags{"-DRF_TEST_A=1", "-DRF_TEST_B=1,2"};
  EXPECT_EQ(manifest.at("extra_flags"), flags);
  manifest["stand_in"] = false;
  const auto binary = other.path() / "rfrecon_520n_emulator.aocx";
  std::ofstream(binary.string() + ".json") << manifest.dump(2);
  EXPECT_EQ(check_binary_manifest(binary, host_manifest_expectation(intel_)).extra_flags, flags);
  manifest["extra_flags"] = {"-DRF_TEST_A=1", 2};
  std::ofstream(binary.string() + ".json") << manifest.dump(2);
  EXPECT_THAT(refusal(binary, "extra_flags"), HasSubstr("array of strings"));
}

// The binary's target against the device's emulation: an emulator binary is refused on a board, a hardware one on
// the emulator, and a report (aoc -rtl, no binary a device loads) on both.
TEST_F(BinaryManifestTest, EmulatorBinaryOnABoardIsRefused) {
  const auto binary = write(real_manifest());
  DeviceInfo board = intel_;
  board.fpga_emulation.clear();
  const std::string message = refusal(binary, "target", &board);
  EXPECT_THAT(message, HasSubstr("expected \"hardware\""));
  EXPECT_THAT(message, HasSubstr("found \"emulator\""));
}

TEST_F(BinaryManifestTest, HardwareBinaryOnTheEmulatorIsRefused) {
  auto manifest = real_manifest();
  manifest["target"] = "hardware";
  const auto binary = write(manifest);
  EXPECT_THAT(refusal(binary, "target"), HasSubstr("expected \"emulator\""));
  DeviceInfo board = intel_;
  board.fpga_emulation.clear();
  EXPECT_NO_THROW((void)check_binary_manifest(binary, host_manifest_expectation(board)));
}

TEST_F(BinaryManifestTest, ReportIsRefused) {
  auto manifest = real_manifest();
  manifest["target"] = "report";
  const auto binary = write(manifest);
  EXPECT_THAT(refusal(binary, "target"), HasSubstr("report-only"));
  DeviceInfo board = intel_;
  board.fpga_emulation.clear();
  EXPECT_THAT(refusal(binary, "target", &board), HasSubstr("report-only"));
}

// On XRT the target must be XCL_EMULATION_MODE's, or hw when it is not set.
TEST_F(BinaryManifestTest, XrtTargetIsTheEmulationMode) {
  auto manifest = real_manifest();
  manifest["target_macro"] = "RF_TARGET_XILINX_FPGA";
  manifest["target"] = "sw_emu";
  const auto binary = write(manifest);
  DeviceInfo xilinx;
  xilinx.xilinx_fpga = true;
  xilinx.fpga_emulation = "sw_emu";
  EXPECT_NO_THROW((void)check_binary_manifest(binary, host_manifest_expectation(xilinx)));
  xilinx.fpga_emulation = "hw_emu";
  EXPECT_THAT(refusal(binary, "target", &xilinx), HasSubstr("XCL_EMULATION_MODE=hw_emu"));
  xilinx.fpga_emulation.clear();
  EXPECT_THAT(refusal(binary, "target", &xilinx), HasSubstr("expected \"hw\""));
}

// Other devices (a PoCL device made to look like a board) have no flow target: any is accepted.
TEST_F(BinaryManifestTest, OtherDevicesTakeAnyTarget) {
  auto manifest = real_manifest();
  manifest["target_macro"] = "";
  const auto binary = write(manifest);
  DeviceInfo accelerator;
  accelerator.kind = DeviceKind::kAccelerator;
  EXPECT_TRUE(host_manifest_expectation(accelerator).target.empty());
  EXPECT_NO_THROW((void)check_binary_manifest(binary, host_manifest_expectation(accelerator)));
}

// Where an FPGA device's emulation comes from: Intel's emulation platform or device, the legacy emulator's variable,
// XRT's XCL_EMULATION_MODE.
TEST(ManifestTargetTest, DeviceEmulationIsDetectedFromThePlatformAndTheEnvironment) {
  const ScopedEnv no_legacy("CL_CONTEXT_EMULATOR_DEVICE_INTELFPGA", nullptr);
  const ScopedEnv no_xrt("XCL_EMULATION_MODE", nullptr);
  DeviceInfo intel;
  intel.intel_fpga = true;
  intel.platform_name = "Intel(R) FPGA SDK for OpenCL(TM)";
  intel.device_name = "p520_max_sg280l : BittWare Stratix 10 OpenCL platform (aclbitt_s10_pcie0)";
  EXPECT_EQ(detect_fpga_emulation(intel), "");
  intel.platform_name = "Intel(R) FPGA Emulation Platform for OpenCL(TM)";
  intel.device_name = "Intel(R) FPGA Emulation Device";
  EXPECT_EQ(detect_fpga_emulation(intel), "emulator");
  DeviceInfo xilinx;
  xilinx.xilinx_fpga = true;
  xilinx.platform_name = "Xilinx";
  EXPECT_EQ(detect_fpga_emulation(xilinx), "");
  {
    const ScopedEnv legacy("CL_CONTEXT_EMULATOR_DEVICE_INTELFPGA", "1");
    const ScopedEnv xrt("XCL_EMULATION_MODE", "sw_emu");
    EXPECT_EQ(detect_fpga_emulation(xilinx), "sw_emu");
    intel.platform_name = "Intel(R) FPGA SDK for OpenCL(TM)";
    intel.device_name = "EmulatorDevice";
    EXPECT_EQ(detect_fpga_emulation(intel), "emulator");
    EXPECT_EQ(detect_fpga_emulation(DeviceInfo{}), "") << "a CPU emulates nothing";
  }
}

TEST_F(BinaryManifestTest, StandInOutputIsRefused) {
  const auto binary = write(*flow_manifest_);
  EXPECT_THAT(refusal(binary, "stand_in"), HasSubstr("stand-in"));
}

TEST_F(BinaryManifestTest, WrongKIsRefusedWithBothValues) {
  auto manifest = real_manifest();
  manifest["parameters"]["RF_K"] = RF_K * 2;
  const std::string message = refusal(write(manifest), "parameters.RF_K");
  EXPECT_THAT(message, HasSubstr("expected " + std::to_string(RF_K)));
  EXPECT_THAT(message, HasSubstr("found " + std::to_string(RF_K * 2)));
}

// The flow configured for another K writes that K into its header and manifest: the host, built for RF_K, refuses it.
TEST_F(BinaryManifestTest, FlowBuiltForAnotherKIsRefused) {
  const rfrecon::testing::TempDir other("manifest_flow_k");
  auto manifest = run_flow(other.path(), "-DRFRECON_K=" + std::to_string(RF_K * 2));
  manifest["stand_in"] = false;
  const std::string message = refusal(write(manifest), "parameters.RF_K");
  EXPECT_THAT(message, HasSubstr("found " + std::to_string(RF_K * 2)));
}

TEST_F(BinaryManifestTest, WrongInterleaveIsRefused) {
  auto manifest = real_manifest();
  manifest["parameters"]["RF_INTEGRATE_INTERLEAVE"] = RF_INTEGRATE_INTERLEAVE + 1;
  (void)refusal(write(manifest), "parameters.RF_INTEGRATE_INTERLEAVE");
  manifest = real_manifest();
  manifest["parameters"]["RF_FUSE_INTERLEAVE"] = RF_FUSE_INTERLEAVE - 1;
  (void)refusal(write(manifest), "parameters.RF_FUSE_INTERLEAVE");
}

TEST_F(BinaryManifestTest, OtherDotSpacingsAreRefused) {
  auto manifest = real_manifest();
  manifest["parameters"]["RF_DOT_SPACINGS"] = {4, 8};
  (void)refusal(write(manifest), "parameters.RF_DOT_SPACINGS");
}

TEST_F(BinaryManifestTest, MissingOrUnknownParameterIsRefused) {
  auto manifest = real_manifest();
  manifest["parameters"].erase("RF_MAX_ROW_WIDTH");
  EXPECT_THAT(refusal(write(manifest), "parameters.RF_MAX_ROW_WIDTH"), HasSubstr("missing"));
  manifest = real_manifest();
  manifest["parameters"]["RF_NEW"] = 1;
  (void)refusal(write(manifest), "parameters.RF_NEW");
}

TEST_F(BinaryManifestTest, OtherSourcesAreRefused) {
  auto manifest = real_manifest();
  std::string hash = manifest["source_sha256"];
  hash[0] = hash[0] == '0' ? '1' : '0';
  manifest["source_sha256"] = hash;
  EXPECT_THAT(refusal(write(manifest), "source_sha256"), HasSubstr(std::string(embedded_kernel_sources_sha256())));
}

TEST_F(BinaryManifestTest, MissingKernelIsRefused) {
  auto manifest = real_manifest();
  auto& kernels = manifest["kernels"];
  kernels.erase(std::find(kernels.begin(), kernels.end(), "dot_frames_single"));
  EXPECT_THAT(refusal(write(manifest), "kernels"), HasSubstr("dot_frames_single"));
}

// An xclbin of the HLS C++ tops (the Vitis 2023.1 flow) records RF_TARGET_HLS, which AMD/Xilinx boards run and
// Intel boards do not.
TEST_F(BinaryManifestTest, HlsTopsBinaryIsForAmdBoardsOnly) {
  auto manifest = real_manifest();
  manifest["target_macro"] = "RF_TARGET_HLS";
  manifest["target"] = "hw";
  manifest["source_sha256"] = std::string(embedded_hls_sources_sha256());
  const auto binary = write(manifest);
  DeviceInfo xilinx;
  xilinx.xilinx_fpga = true;
  EXPECT_NO_THROW((void)check_binary_manifest(binary, host_manifest_expectation(xilinx)));
  EXPECT_THAT(refusal(binary, "target_macro"), HasSubstr("expected \"RF_TARGET_INTEL_FPGA\""));
}

// The u250 flow of the HLS C++ tops (a Vitis 2023.1 stand-in) hashes hw/hls with the kernels, as the host does: its
// manifest is accepted for an AMD board, and the same manifest with the kernels-only hash is refused.
TEST_F(BinaryManifestTest, HlsBinaryHashCoversTheTops) {
  rfrecon::testing::TempDir hls("manifest_flow_hls");
  const StandInFlow flow = u250_hls_sw_emu();
  auto manifest = run_flow(hls.path(), "", flow);
  ASSERT_FALSE(manifest.empty());
  EXPECT_EQ(manifest.at("target_macro"), "RF_TARGET_HLS");
  const auto binary = hls.path() / flow.binary;
  manifest["stand_in"] = false;
  std::ofstream(binary.string() + ".json") << manifest.dump(2);
  DeviceInfo xilinx;
  xilinx.xilinx_fpga = true;
  xilinx.fpga_emulation = "sw_emu";
  EXPECT_NO_THROW((void)check_binary_manifest(binary, host_manifest_expectation(xilinx)));
  manifest["source_sha256"] = std::string(embedded_kernel_sources_sha256());
  std::ofstream(binary.string() + ".json") << manifest.dump(2);
  EXPECT_THAT(refusal(binary, "source_sha256", &xilinx), HasSubstr("HLS C++ tops"));
}

// The u250 flow at Vitis 2025.1 compiles the tops with v++ -c --mode hls: the hardware emulation binary's manifest has
// the tops' hash and is accepted under XCL_EMULATION_MODE=hw_emu, refused under sw_emu and on a board; a binary
// changed since (the one file the host loads) is refused naming it.
TEST_F(BinaryManifestTest, HlsModeBinaryOfVitis2025IsChecked) {
  rfrecon::testing::TempDir hls("manifest_flow_hls_mode");
  const StandInFlow flow = u250_hls_mode_hw_emu();
  auto manifest = run_flow(hls.path(), "", flow);
  ASSERT_FALSE(manifest.empty());
  EXPECT_EQ(manifest.at("tool_version"), "2025.1");
  EXPECT_EQ(manifest.at("target"), "hw_emu");
  EXPECT_EQ(manifest.at("source_sha256"), std::string(embedded_hls_sources_sha256()));
  const auto binary = hls.path() / flow.binary;
  manifest["stand_in"] = false;
  std::ofstream(binary.string() + ".json") << manifest.dump(2);
  DeviceInfo xilinx;
  xilinx.xilinx_fpga = true;
  xilinx.fpga_emulation = "hw_emu";
  EXPECT_NO_THROW((void)check_binary_manifest(binary, host_manifest_expectation(xilinx)));
  xilinx.fpga_emulation = "sw_emu";
  EXPECT_THAT(refusal(binary, "target", &xilinx), HasSubstr("found \"hw_emu\""));
  xilinx.fpga_emulation.clear();
  (void)refusal(binary, "target", &xilinx);
  xilinx.fpga_emulation = "hw_emu";
  std::ofstream(binary, std::ios::app) << "relinked";
  EXPECT_THAT(refusal(binary, "binary_sha256", &xilinx), HasSubstr(flow.binary));
}

TEST_F(BinaryManifestTest, OtherTargetMacroIsRefused) {
  const auto binary = write(real_manifest());
  DeviceInfo xilinx;
  xilinx.xilinx_fpga = true;
  EXPECT_THAT(refusal(binary, "target_macro", &xilinx), HasSubstr("RF_TARGET_XILINX_FPGA"));
}

TEST_F(BinaryManifestTest, ManifestOfAnotherBinaryIsRefused) {
  auto manifest = real_manifest();
  const auto binary = write(manifest);
  std::filesystem::rename(binary, temp_.path() / "renamed.aocx");
  std::filesystem::rename(binary.string() + ".json", temp_.path() / "renamed.aocx.json");
  (void)refusal(temp_.path() / "renamed.aocx", "binary");
}

TEST_F(BinaryManifestTest, MissingManifestIsRefused) {
  const auto binary = temp_.path() / "board.aocx";
  std::ofstream(binary) << "binary";
  EXPECT_THAT(refusal(binary, ""), HasSubstr("missing"));
}

TEST_F(BinaryManifestTest, MalformedManifestIsRefused) {
  const std::string truncated = real_manifest().dump().substr(0, 40);
  EXPECT_THAT(refusal(write(real_manifest(), truncated), ""), HasSubstr("not valid JSON"));
  EXPECT_THAT(refusal(write(real_manifest(), "[1, 2]"), ""), HasSubstr("not a JSON object"));
  auto manifest = real_manifest();
  manifest.erase("tool_version");
  EXPECT_THAT(refusal(write(manifest), "tool_version"), HasSubstr("missing"));
  manifest = real_manifest();
  manifest["stand_in"] = "no";
  EXPECT_THAT(refusal(write(manifest), "stand_in"), HasSubstr("true or false"));
  manifest = real_manifest();
  manifest["kernels"] = {"axpy_single", 3};
  (void)refusal(write(manifest), "kernels");
}

TEST_F(BinaryManifestTest, BuildOptionsMayOnlyRestateTheParameters) {
  const BinaryManifest checked = check_binary_manifest(write(real_manifest()), host_manifest_expectation(intel_));
  check_options_match_manifest(checked, "");
  check_options_match_manifest(checked, "-DRF_K=" + std::to_string(RF_K));
  const auto refused = [&](const std::string& options, const std::string& field) {
    try {
      check_options_match_manifest(checked, options);
      ADD_FAILURE() << options << " accepted";
    } catch (const BinaryManifestError& error) {
      EXPECT_EQ(error.field(), field) << error.what();
      EXPECT_THAT(error.what(), HasSubstr(options));
    }
  };
  refused("-DRF_K=" + std::to_string(RF_K + 1), "parameters.RF_K");
  refused("-DRF_OTHER=1", "parameters");
  refused("-cl-fast-relaxed-math", "parameters");
}

TEST_F(BinaryManifestTest, DirectoryMustHoldExactlyOneBinaryWithManifest) {
  std::ofstream(temp_.path() / "emconfig.json") << "{}";  // an emulation file, no binary beside it
  try {
    (void)find_board_binary(temp_.path());
    FAIL() << "a directory without a binary accepted";
  } catch (const BinaryManifestError& error) {
    EXPECT_THAT(error.what(), HasSubstr("no kernel binary"));
  }
  const auto binary = write(real_manifest());
  EXPECT_EQ(find_board_binary(temp_.path()), binary);
  auto other = real_manifest();
  other["binary"] = "rfrecon_520n.aocx";
  (void)write(other);
  try {
    (void)find_board_binary(temp_.path());
    FAIL() << "two binaries accepted";
  } catch (const BinaryManifestError& error) {
    EXPECT_THAT(error.what(), HasSubstr("rfrecon_520n.aocx"));
    EXPECT_THAT(error.what(), HasSubstr(binary.filename().string()));
  }
}

}  // namespace
}  // namespace rfrecon::cl
