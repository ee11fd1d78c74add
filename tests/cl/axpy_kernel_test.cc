// The self-check kernel against its C++ reference, through both entries, on every selected device.
#include <gtest/gtest.h>

#include "host/cl/device_selection.h"
#include "host/selfcheck/axpy.h"

namespace rfrecon::selfcheck {
namespace {

TEST(AxpyKernelTest, BothEntriesMatchReferenceExactlyOnEveryDevice) {
  std::vector<float> x(1000);
  std::vector<float> y(1000);
  for (std::size_t i = 0; i < x.size(); ++i) {
    x[i] = 0.001f * static_cast<float>(i) - 0.3f;
    y[i] = static_cast<float>(i % 13) * 1.7f;
  }
  const auto expected = axpy_reference(-2.5f, x, y);
  cl::ProgramCache programs;
  auto devices = cl::open_devices("");
  ASSERT_FALSE(devices.empty());
  for (auto& device : devices) {
    for (const auto entry : {KernelEntry::kNdRange, KernelEntry::kSingleWorkItem}) {
      // fma is correctly rounded in OpenCL C and in C++, so the results agree bit for bit.
      EXPECT_EQ(axpy_opencl(device, programs, entry, -2.5f, x, y), expected) << cl::describe(device.info());
    }
  }
}

}  // namespace
}  // namespace rfrecon::selfcheck
