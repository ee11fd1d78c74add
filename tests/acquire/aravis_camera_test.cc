// The GenICam path through Aravis's own fake cameras: the in-process "Fake" interface for feature control and
// acquisition, and a GigE Vision fake camera on the loopback interface for a camera that disappears mid-run. No
// packet leaves the machine: the Fake suite disables the network interfaces of Aravis (discovery broadcasts), and the
// GigE camera is opened by its loopback address, without discovery.
#include "host/drivers/aravis_camera.h"

#include <arv.h>
#include <gtest/gtest.h>

#include "host/core/errors.h"
#include "host/drivers/open_devices.h"

namespace rfrecon::drivers {
namespace {

class AravisFake : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    arv_disable_interface("GigEVision");
    arv_enable_interface("Fake");
  }
  static void TearDownTestSuite() { arv_enable_interface("GigEVision"); }
};

TEST_F(AravisFake, FeaturesAreLockedAndReadBack) {
  const auto camera = open_camera("aravis:Fake_1");
  const auto format = camera->format();
  EXPECT_EQ(format.size, cv::Size(512, 512));
  EXPECT_EQ(format.bit_depth, 16) << "the deepest monochrome format (Mono16) is chosen";
  EXPECT_NEAR(camera->lock_exposure(5000.0), 5000.0, 1.0);
  EXPECT_NEAR(camera->lock_exposure(12345.0), 12345.0, 1.0);
  EXPECT_NEAR(camera->lock_exposure(0.0), 12345.0, 1.0) << "0 keeps the exposure as it is";
}

TEST_F(AravisFake, FramesComeAtTheFormatsSizeAndDepth) {
  const auto camera = open_camera("aravis:Fake_1");
  camera->lock_exposure(2000.0);
  for (int i = 0; i < 3; ++i) {
    const cv::Mat frame = camera->grab(std::chrono::milliseconds(2000));
    EXPECT_EQ(frame.size(), camera->format().size);
    EXPECT_EQ(frame.type(), CV_16UC1);
  }
}

TEST_F(AravisFake, UnknownCameraIsAHardwareErrorListingTheCameras) {
  try {
    open_camera("aravis:no-such-camera");
    FAIL() << "no error";
  } catch (const HardwareError& error) {
    EXPECT_NE(std::string(error.what()).find("Fake_1"), std::string::npos) << error.what();
  }
}

TEST(AravisGigEVision, CameraThatDisappearsIsAHardwareErrorNamingIt) {
  ArvGvFakeCamera* fake = arv_gv_fake_camera_new("lo", "RF01");
  ASSERT_NE(fake, nullptr);
  if (!arv_gv_fake_camera_is_running(fake)) {
    g_object_unref(fake);
    GTEST_SKIP() << "no GigE Vision fake camera on the loopback interface here";
  }
  auto camera = open_camera("aravis:127.0.0.1");
  EXPECT_FALSE(camera->grab(std::chrono::milliseconds(2000)).empty());
  g_object_unref(fake);  // unplugged
  try {
    for (int i = 0; i < 8; ++i) camera->grab(std::chrono::milliseconds(500));  // buffered frames drain first
    FAIL() << "no error";
  } catch (const HardwareError& error) {
    const std::string message = error.what();
    EXPECT_NE(message.find("127.0.0.1"), std::string::npos) << message;
    EXPECT_NE(message.find("sent no frame within 500 ms"), std::string::npos) << message;
  }
}

}  // namespace
}  // namespace rfrecon::drivers
