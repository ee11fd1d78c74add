// `rfrecon reconstruct` on bad input: each case ends with its documented exit code and a message naming the
// problem, and leaves no output directory behind.
#include <filesystem>

#include <gtest/gtest.h>

#include "calib/rig.h"
#include "host/transport/transport_file.h"
#include "sim/builtin_scenes.h"
#include "sim/truth_io.h"
#include "tests/common/run_cli.h"
#include "tests/sim/test_scenes.h"
#include "tests/transport/synthetic_capture.h"

namespace rfrecon {
namespace {

namespace fs = std::filesystem;

class ReconstructCliTest : public ::testing::Test {
 protected:
  void SetUp() override {
    // An 80x60 T in which no camera pixel has a correspondence, and the true rig of an 80x60 rig.
    transport::TransportSetup setup;
    setup.camera_size = setup.projector_size = cv::Size(80, 60);
    transport::write_transport(transport::make_empty_transport(setup), dir_ / "T.h5");
    small_rig_ = sim::true_rig(sim::testing::make_scene(
        sim::testing::small_rig({sim::testing::tilted_plane({{"brdf", "lambert"}, {"diffuse", 0.5}})})));
    calib::write_rig(small_rig_, dir_ / "rig.yaml");
  }
  testing::CliResult reconstruct(const fs::path& rig) {
    return testing::run_cli("reconstruct " + (dir_ / "T.h5").string() + " --calib " + rig.string() + " -o " +
                            (dir_ / "out").string());
  }

  transport::testing::TempDir temp_{"reconstruct_cli"};
  const fs::path& dir_ = temp_.path();
  calib::StereoRig small_rig_;
};

TEST_F(ReconstructCliTest, EverythingMaskedIsAProcessingError) {
  const auto result = reconstruct(dir_ / "rig.yaml");
  EXPECT_EQ(result.exit_code, 6) << result.output;
  EXPECT_NE(result.output.find("nothing to reconstruct"), std::string::npos) << result.output;
  EXPECT_FALSE(fs::exists(dir_ / "out"));
}

TEST_F(ReconstructCliTest, CalibrationOfAnotherSizeIsAnInputError) {
  calib::write_rig(sim::true_rig(sim::builtin_scene("cube-anisotropic")), dir_ / "big.yaml");
  const auto result = reconstruct(dir_ / "big.yaml");
  EXPECT_EQ(result.exit_code, 3) << result.output;
  EXPECT_NE(result.output.find("different sizes"), std::string::npos) << result.output;
  EXPECT_FALSE(fs::exists(dir_ / "out"));
}

TEST_F(ReconstructCliTest, CalibrationThatCannotBeRectifiedIsAnInputError) {
  calib::StereoRig vertical = small_rig_;
  vertical.P2.at<double>(1, 3) = -100.0 * vertical.P2.at<double>(1, 1);  // a vertical baseline
  calib::write_rig(vertical, dir_ / "vertical.yaml");
  const auto result = reconstruct(dir_ / "vertical.yaml");
  EXPECT_EQ(result.exit_code, 3) << result.output;
  EXPECT_NE(result.output.find("vertical.yaml: cannot rectify"), std::string::npos) << result.output;
  EXPECT_FALSE(fs::exists(dir_ / "out"));
}

TEST_F(ReconstructCliTest, MissingTransportIsAnInputError) {
  const auto result = testing::run_cli("reconstruct " + (dir_ / "none.h5").string() + " --calib " +
                                       (dir_ / "rig.yaml").string() + " -o " + (dir_ / "out").string());
  EXPECT_EQ(result.exit_code, 3) << result.output;
  EXPECT_NE(result.output.find("none.h5"), std::string::npos) << result.output;
  EXPECT_FALSE(fs::exists(dir_ / "out"));
}

}  // namespace
}  // namespace rfrecon
