// `rfrecon capture`'s refusals: an existing output, no display, no camera, an unknown camera kind each end with a
// clear message and exit code, and leave nothing behind.
#include <fstream>
#include <string>

#include <gtest/gtest.h>

#include "tests/common/run_cli.h"
#include "tests/common/temp_dir.h"

namespace rfrecon {
namespace {

namespace fs = std::filesystem;
using testing::run_cli;

TEST(CaptureCli, ExistingCaptureIsNeverReplacedWithoutForce) {
  testing::TempDir dir("capture_existing");
  std::ofstream(dir.path() / "keep.txt") << "a user's file";
  const auto result = run_cli("capture --camera sim:cube-anisotropic -o " + dir.path().string());
  EXPECT_EQ(result.exit_code, 2) << result.output;
  EXPECT_TRUE(fs::exists(dir.path() / "keep.txt"));
}

TEST(CaptureCli, NoDisplayIsAHardwareErrorSayingWhatToSet) {
  testing::TempDir dir("capture_no_display");
  const auto result = run_cli(
      "capture --projector display:0 --camera 'gst:videotestsrc ! appsink' -o " + (dir.path() / "capture").string(),
      "env -u DISPLAY -u WAYLAND_DISPLAY SDL_VIDEODRIVER=x11");
  EXPECT_EQ(result.exit_code, 10) << result.output;
  EXPECT_NE(result.output.find("no display"), std::string::npos) << result.output;
  EXPECT_TRUE(fs::is_empty(dir.path()));
}

TEST(CaptureCli, MissingCameraIsAHardwareErrorNamingIt) {
  testing::TempDir dir("capture_no_camera");
  const auto result =
      run_cli("capture --projector display:0 --camera v4l2:/dev/video-none -o " + (dir.path() / "capture").string());
  EXPECT_EQ(result.exit_code, 10) << result.output;
  EXPECT_NE(result.output.find("/dev/video-none"), std::string::npos) << result.output;
  EXPECT_TRUE(fs::is_empty(dir.path()));
}

TEST(CaptureCli, UnknownCameraKindIsAUsageError) {
  const auto result = run_cli("capture --camera firewire:0 --projector display:0 -o unused");
  EXPECT_EQ(result.exit_code, 2) << result.output;
  EXPECT_NE(result.output.find("v4l2:DEVICE"), std::string::npos) << result.output;
}

}  // namespace
}  // namespace rfrecon
