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
#include "tests/common/temp_dir.h"

namespace rfrecon::cl {
namespace {

using ::testing::HasSubstr;

// A stand-in flow of hw/: the board, the stand-in tools as configure options, the environment of both steps, the
// target built and the binary it writes (beside it, its manifest).
struct StandInFlow {
  std::string board, tools, environment, target, binary;
};
StandInFlow intel_emulator() {
  return {"520n", "-DRFRECON_AOC=\"" + std::string(RFRECON_SOURCE_DIR) + "/tests/fpga/bin/aoc\"", "",
          "rfrecon_fpga_emulator", "rfrecon_520n_emulator.aocx"};
}
// The u250 flow of the HLS C++ tops, as Vitis 2023.1 and later build them.
StandInFlow u250_hls_sw_emu() {
  const std::string bin = std::string(RFRECON_SOURCE_DIR) + "/tests/fpga/bin";
  return {"u250", "-DRFRECON_VXX=\"" + bin + "/v++\" -DRFRECON_EMCONFIGUTIL=\"" + bin + "/emconfigutil\"",
          "RFRECON_STANDIN_VERSION=2023.1 ", "rfrecon_fpga_sw_emu", "rfrecon_u250_sw_emu.xclbin"};
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

// The flow records RFRECON_FPGA_EXTRA_FLAGS in the manifest, one string per flag, and the host reads them back.
TEST_F(BinaryManifestTest, ExtraFlagsAreRecorded) {
  EXPECT_EQ(real_manifest().at("extra_flags"), nlohmann::json::array());
  rfrecon::testing::TempDir other("manifest_flow_flags");
  const auto manifest = run_flow(other.path(), "\"-DRFRECON_FPGA_EXTRA_FLAGS=-DRF_TEST_A=1;-DRF_TEST_B=1,2\"");
  EXPECT_EQ(manifest.at("extra_flags"), (nlohmann::json{"-DRF_TEST_A=1", "-DRF_TEST_B=1,2"}));
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
  EXPECT_NO_THROW((void)check_binary_manifest(binary, host_manifest_expectation(xilinx)));
  manifest["source_sha256"] = std::string(embedded_kernel_sources_sha256());
  std::ofstream(binary.string() + ".json") << manifest.dump(2);
  EXPECT_THAT(refusal(binary, "source_sha256", &xilinx), HasSubstr("HLS C++ tops"));
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
