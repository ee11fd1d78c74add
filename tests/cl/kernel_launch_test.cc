// Kernel names, argument setting, launch sizes and the buffer helpers of host/cl/kernel_launch.h, on PoCL.
#include "host/cl/kernel_launch.h"

#include <algorithm>
#include <cstdint>
#include <string>

#include <gtest/gtest.h>

#include "host/cl/device_selection.h"
#include "host/cl/program_cache.h"
#include "host/selfcheck/axpy.h"
#include "tests/common/devices.h"

namespace rfrecon::cl {
namespace {

using rfrecon::testing::first_device;

TEST(KernelLaunchTest, KernelNameFollowsTheEntry) {
  EXPECT_EQ(kernel_name("axpy", KernelEntry::kNdRange), "axpy_ndrange");
  EXPECT_EQ(kernel_name("axpy", KernelEntry::kSingleWorkItem), "axpy_single");
}

TEST(KernelLaunchTest, UploadAndDownloadRoundTrip) {
  auto device = first_device();
  const std::vector<std::int32_t> values{-1, 0, 7, 1 << 30};
  const ::cl::Buffer buffer = upload(device.context(), values, CL_MEM_READ_WRITE);
  EXPECT_EQ(download<std::int32_t>(device.queue(), buffer, values.size()), values);
  const std::vector<std::int32_t> other{5, 6};
  write_buffer(device.queue(), buffer, other.data(), other.size());
  EXPECT_EQ(download<std::int32_t>(device.queue(), buffer, values.size()),
            (std::vector<std::int32_t>{5, 6, 7, 1 << 30}));
  // Empty inputs still make a valid buffer (one element), so kernels can take it as an argument.
  const ::cl::Buffer empty = upload(device.context(), std::vector<float>{});
  EXPECT_EQ(empty.getInfo<CL_MEM_SIZE>(), sizeof(float));
  EXPECT_EQ(make_buffer<double>(device.context(), 0).getInfo<CL_MEM_SIZE>(), sizeof(double));
}

TEST(KernelLaunchTest, GrowingBufferReallocatesOnlyToGrow) {
  auto device = first_device();
  GrowingBuffer growing;
  const cl_mem first = growing.at_least(device.context(), 64, CL_MEM_READ_ONLY)();
  EXPECT_EQ(growing.at_least(device.context(), 16, CL_MEM_READ_ONLY)(), first);
  EXPECT_EQ(growing.buffer()(), first);
  const ::cl::Buffer& grown = growing.at_least(device.context(), 128, CL_MEM_READ_ONLY);
  EXPECT_NE(grown(), first);
  EXPECT_EQ(grown.getInfo<CL_MEM_SIZE>(), 128U);
}

// Both entries, a fixed work-group size that does not divide the item count, and events chaining two launches.
TEST(KernelLaunchTest, EnqueueCoversEveryItemInEachLaunchShape) {
  auto device = first_device();
  ProgramCache programs;
  std::vector<float> x(100), y(100);
  for (std::size_t i = 0; i < x.size(); ++i) {
    x[i] = static_cast<float>(i) * 0.25f;
    y[i] = 3.0f - static_cast<float>(i);
  }
  const auto twice = selfcheck::axpy_reference(1.5f, x, selfcheck::axpy_reference(1.5f, x, y));
  struct Shape {
    KernelEntry entry;
    std::size_t work_group;
  };
  for (const Shape shape :
       {Shape{KernelEntry::kNdRange, 0}, Shape{KernelEntry::kNdRange, 64}, Shape{KernelEntry::kSingleWorkItem, 64}}) {
    ::cl::Kernel kernel = make_kernel(programs.get(device, "selfcheck/axpy.cl"), "axpy", shape.entry);
    const ::cl::Buffer xb = upload(device.context(), x);
    const ::cl::Buffer yb = upload(device.context(), y, CL_MEM_READ_WRITE);
    set_args(kernel, 1.5f, xb, yb, static_cast<cl_uint>(x.size()));
    std::vector<::cl::Event> first(1);
    const std::size_t group = std::min(shape.work_group, device.info().max_work_group_size);
    enqueue_kernel(device.queue(), kernel, shape.entry, x.size(), {group, nullptr, &first[0]});
    enqueue_kernel(device.queue(), kernel, shape.entry, x.size(), {group, &first});
    std::vector<float> out(y.size());
    read_buffer(device.queue(), yb, out.data(), out.size());
    EXPECT_EQ(out, twice) << kernel_name("axpy", shape.entry) << " work_group " << shape.work_group;
  }
}

TEST(KernelLaunchApiErrorTest, UnknownKernelIsNamed) {
  auto device = first_device();
  ProgramCache programs;
  try {
    (void)make_kernel(programs.get(device, "selfcheck/axpy.cl"), "nonexistent", KernelEntry::kSingleWorkItem);
    FAIL() << "expected ClError";
  } catch (const ClError& error) {
    EXPECT_NE(std::string(error.what()).find("nonexistent_single"), std::string::npos) << error.what();
  }
}

}  // namespace
}  // namespace rfrecon::cl
