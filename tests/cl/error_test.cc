// ClError and BuildError carry the call, the code's name and the location.
#include "host/cl/error.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

namespace rfrecon::cl {
namespace {

using ::testing::HasSubstr;

TEST(ClErrorTest, NamesCallCodeAndLocation) {
  try {
    RF_CL_CHECK(static_cast<cl_int>(CL_INVALID_VALUE));
    FAIL() << "expected a ClError";
  } catch (const ClError& error) {
    EXPECT_EQ(error.code(), CL_INVALID_VALUE);
    EXPECT_THAT(error.what(), HasSubstr("CL_INVALID_VALUE (-30)"));
    EXPECT_THAT(error.what(), HasSubstr("error_test.cc:"));
    EXPECT_THAT(error.call(), HasSubstr("CL_INVALID_VALUE"));
  }
}

TEST(ClErrorTest, SuccessDoesNotThrow) { EXPECT_NO_THROW(RF_CL_CHECK_CODE(CL_SUCCESS, "clFinish")); }

TEST(ClErrorTest, UnknownCodesAreNamedByNumber) { EXPECT_EQ(error_name(-12345), "CL_UNKNOWN_ERROR(-12345)"); }

}  // namespace
}  // namespace rfrecon::cl
