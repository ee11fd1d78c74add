// Embedded kernel sources are present and their includes are resolved.
#include "host/cl/kernel_sources.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

namespace rfrecon::cl {
namespace {

using ::testing::HasSubstr;
using ::testing::Not;

TEST(KernelSourcesTest, IncludesAreInlinedOnce) {
  const std::string source = resolve_kernel_source("selfcheck/axpy.cl");
  EXPECT_THAT(source, HasSubstr("#define RF_SINGLE_TASK"));
  EXPECT_THAT(source, HasSubstr("__kernel void axpy_ndrange"));
  EXPECT_THAT(source, Not(HasSubstr("#include \"common/target.h\"")));
}

TEST(KernelSourcesTest, MissingFileIsNamed) {
  try {
    (void)embedded_kernel_file("nope/missing.cl");
    FAIL() << "expected an error";
  } catch (const std::out_of_range& error) {
    EXPECT_THAT(error.what(), HasSubstr("nope/missing.cl"));
  }
}

}  // namespace
}  // namespace rfrecon::cl
