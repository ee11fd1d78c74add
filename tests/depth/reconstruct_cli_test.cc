// `rfrecon reconstruct` on bad input: each case ends with its documented exit code and a message naming the
// problem, and leaves no output directory behind.
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

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
    setup.dot_spacing = 8;
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

// The edge correction reads T's white frame; this T has none (as one written before it was kept).
TEST_F(ReconstructCliTest, EdgeCorrectionWithoutTheWhiteFrameIsAnInputError) {
  const auto result =
      testing::run_cli("reconstruct " + (dir_ / "T.h5").string() + " --calib " + (dir_ / "rig.yaml").string() + " -o " +
                       (dir_ / "out").string() + " --edge-footprint 0.5");
  EXPECT_EQ(result.exit_code, 3) << result.output;
  EXPECT_NE(result.output.find("no white frame"), std::string::npos) << result.output;
  EXPECT_FALSE(fs::exists(dir_ / "out"));
}

TEST_F(ReconstructCliTest, CalibrationOfAnotherSizeIsAnInputError) {
  calib::write_rig(sim::true_rig(sim::builtin_scene("cube-anisotropic")), dir_ / "big.yaml");
  const auto result = reconstruct(dir_ / "big.yaml");
  EXPECT_EQ(result.exit_code, 3) << result.output;
  EXPECT_NE(result.output.find("different sizes"), std::string::npos) << result.output;
  EXPECT_FALSE(fs::exists(dir_ / "out"));
}

TEST_F(ReconstructCliTest, DegenerateCalibrationIsAnInputErrorNamingTheKey) {
  calib::StereoRig no_baseline = small_rig_;
  no_baseline.proj_from_cam_translation_mm = cv::Mat::zeros(3, 1, CV_64F);  // camera and projector centres coincide
  calib::write_rig(no_baseline, dir_ / "no_baseline.yaml");
  auto result = reconstruct(dir_ / "no_baseline.yaml");
  EXPECT_EQ(result.exit_code, 3) << result.output;
  EXPECT_NE(result.output.find("no_baseline.yaml: key 'T'"), std::string::npos) << result.output;

  // A NaN focal length, written as OpenCV writes it.
  std::ifstream in(dir_ / "rig.yaml");
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const auto data = text.find("data: [", text.find("camera_matrix:")) + 8;
  text.replace(data, text.find(',', data) - data, ".nan");
  std::ofstream(dir_ / "nan.yaml") << text;
  result = reconstruct(dir_ / "nan.yaml");
  EXPECT_EQ(result.exit_code, 3) << result.output;
  EXPECT_NE(result.output.find("nan.yaml: key 'camera_matrix' holds a value that is not finite"), std::string::npos)
      << result.output;
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
