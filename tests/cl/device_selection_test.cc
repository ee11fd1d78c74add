// Device selection by type, index and name, on whatever OpenCL devices the machine has (PoCL in CI).
#include "host/cl/device_selection.h"

#include <cstdlib>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "host/cl/error.h"

namespace rfrecon::cl {
namespace {

using ::testing::HasSubstr;

TEST(DeviceSelectionTest, AllSelectsEveryDeviceOnce) {
  const auto available = enumerate_devices();
  ASSERT_FALSE(available.empty()) << "no OpenCL device: install pocl-opencl-icd (scripts/setup.sh)";
  EXPECT_EQ(select_devices(available, "all").size(), available.size());
  EXPECT_EQ(select_devices(available, "all,0,cpu").size(), available.size() == 1 ? 1U : available.size());
}

TEST(DeviceSelectionTest, ByIndexAndByName) {
  const auto available = enumerate_devices();
  ASSERT_FALSE(available.empty());
  const auto by_index = select_devices(available, "0");
  ASSERT_EQ(by_index.size(), 1U);
  EXPECT_EQ(by_index.front().info.index, 0);
  // A case-insensitive piece of the device name selects it.
  std::string piece = available.front().info.device_name.substr(0, 4);
  for (char& c : piece) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  const auto by_name = select_devices(available, piece);
  ASSERT_FALSE(by_name.empty());
  EXPECT_EQ(by_name.front().info.device_name, available.front().info.device_name);
}

TEST(DeviceSelectionTest, UnknownNameListsWhatExists) {
  const auto available = enumerate_devices();
  ASSERT_FALSE(available.empty());
  try {
    (void)select_devices(available, "no-such-device-xyz");
    FAIL() << "expected DeviceSelectionError";
  } catch (const DeviceSelectionError& error) {
    EXPECT_THAT(error.what(), HasSubstr("no OpenCL device matches 'no-such-device-xyz'"));
    EXPECT_THAT(error.what(), HasSubstr(available.front().info.device_name));
  }
  EXPECT_THROW((void)select_devices(available, "0,,1"), DeviceSelectionError);
  EXPECT_THROW((void)select_devices({}, "all"), DeviceSelectionError);
}

TEST(DeviceSelectionTest, FlagBeatsEnvironmentBeatsDefault) {
  ::setenv(kDevicesEnv, "cpu", 1);
  EXPECT_EQ(effective_selection("gpu"), "gpu");
  EXPECT_EQ(effective_selection(""), "cpu");
  ::unsetenv(kDevicesEnv);
  EXPECT_EQ(effective_selection(""), "all");
}

// Run with POCL_DEVICES="pthread pthread" (as ctest does for this test) to see two PoCL devices; each gets its
// own context and queue, and both can be selected together or apart.
TEST(DeviceSelectionTest, TwoPoclDevicesAreDistinct) {
  const auto available = enumerate_devices();
  const char* pocl_devices = std::getenv("POCL_DEVICES");
  if (pocl_devices == nullptr || std::string(pocl_devices) != "pthread pthread") {
    GTEST_SKIP() << "needs POCL_DEVICES=\"pthread pthread\"";
  }
  ASSERT_GE(available.size(), 2U);
  const auto both = select_devices(available, "0,1");
  ASSERT_EQ(both.size(), 2U);
  DeviceContext first(both[0]);
  DeviceContext second(both[1]);
  EXPECT_NE(first.context()(), second.context()());
  EXPECT_NE(first.device()(), second.device()());
  EXPECT_EQ(select_devices(available, "1").front().info.index, 1);
}

}  // namespace
}  // namespace rfrecon::cl
