// The fault-injection grammar of RFRECON_INJECT_FAULT and when a policy fires (hangs: timeout_test.cc).
#include "host/sched/fault.h"

#include <gtest/gtest.h>

#include "host/core/errors.h"

namespace rfrecon::sched {
namespace {

TEST(FaultPolicyTest, FiresOnlyAtTheNamedDeviceAndTile) {
  const auto policy = FaultPolicy::parse("1:3,0:5");
  EXPECT_NO_THROW(policy.check(1, 2));
  EXPECT_THROW(policy.check(1, 3), InjectedFault);
  EXPECT_NO_THROW(policy.check(0, 3));
  EXPECT_THROW(policy.check(0, 5), InjectedFault);
  EXPECT_NO_THROW(policy.check(2, 3));
}

TEST(FaultPolicyTest, StarNamesEveryDevice) {
  const auto policy = FaultPolicy::parse("*:1");
  for (std::size_t device = 0; device < 4; ++device) EXPECT_THROW(policy.check(device, 1), InjectedFault);
  EXPECT_NO_THROW(policy.check(0, 2));
}

TEST(FaultPolicyTest, HangTermsParseAndLeaveOtherTilesAlone) {
  const auto policy = FaultPolicy::parse("hang:1:2,0:1,hang:*:9");
  EXPECT_NO_THROW(policy.check(1, 1));
  EXPECT_THROW(policy.check(0, 1), InjectedFault);
  EXPECT_NO_THROW(policy.check(0, 2));
}

TEST(FaultPolicyTest, InjectedFaultIsAnOpenClError) {
  try {
    FaultPolicy::parse("0:1").check(0, 1);
    FAIL() << "no fault";
  } catch (const cl::ClError& error) {
    EXPECT_EQ(error.code(), CL_DEVICE_NOT_AVAILABLE);
    EXPECT_NE(std::string(error.what()).find(kInjectFaultEnv), std::string::npos);
  }
}

TEST(FaultPolicyTest, MalformedTermsAreInputErrorsNamingTheVariable) {
  for (const char* spec : {"1", "a:1", "1:b", "1:0", "1:2:3", "1:2,x", "hang:1", "hang:", "hang:x:1", "stall:1:2"}) {
    SCOPED_TRACE(spec);
    try {
      FaultPolicy::parse(spec);
      FAIL() << "accepted";
    } catch (const InputError& error) {
      EXPECT_NE(std::string(error.what()).find(kInjectFaultEnv), std::string::npos);
    }
  }
  EXPECT_TRUE(FaultPolicy::parse("").empty());
}

}  // namespace
}  // namespace rfrecon::sched
