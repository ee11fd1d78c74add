// The depth options' table: the defaults lie in their ranges, both ends of each range are taken, a value outside it
// or an unknown name is a UsageError naming the option, and the flags of `rfrecon reconstruct` are the table's.
#include "host/depth/depth_option_table.h"

#include <cmath>
#include <set>
#include <string>

#include <gtest/gtest.h>

#include "host/core/errors.h"
#include "tests/common/run_cli.h"

namespace rfrecon::depth {
namespace {

TEST(DepthOptionTableTest, DefaultsLieInTheirRangesAndBothEndsAreTaken) {
  EXPECT_NO_THROW(check_depth_options(DepthOptions{}));
  for (const auto& spec : depth_option_table()) {
    SCOPED_TRACE(spec.name);
    ASSERT_TRUE((spec.real == nullptr) != (spec.whole == nullptr));
    for (const double value : {spec.low, spec.high}) {
      DepthOptions options;
      set_depth_option(options, spec.name, value);
      const double stored = spec.real != nullptr ? *spec.real(options) : *spec.whole(options);
      EXPECT_NEAR(stored, value, 1e-6 * value);
      EXPECT_NO_THROW(check_depth_options(options));
    }
  }
}

TEST(DepthOptionTableTest, OutOfRangeNotWholeAndUnknownAreUsageErrorsNamingTheOption) {
  for (const auto& spec : depth_option_table()) {
    SCOPED_TRACE(spec.name);
    DepthOptions options;
    for (const double value : {spec.low - 1.0, spec.high * 2.0 + 1.0, std::nan("")}) {
      try {
        set_depth_option(options, spec.name, value);
        ADD_FAILURE() << value << " was taken";
      } catch (const UsageError& e) {
        EXPECT_NE(std::string(e.what()).find(std::string("'") + spec.name + "'"), std::string::npos) << e.what();
      }
    }
    if (spec.whole != nullptr) {
      EXPECT_THROW(set_depth_option(options, spec.name, spec.low + 0.5), UsageError);
      *spec.whole(options) = static_cast<int>(spec.high) + 1;  // set behind the table's back
    } else {
      *spec.real(options) = static_cast<float>(spec.low - 1.0);
    }
    EXPECT_THROW(check_depth_options(options), UsageError);
  }
  try {
    DepthOptions options;
    set_depth_option(options, "no-such-option", 1.0);
    ADD_FAILURE() << "an unknown name was taken";
  } catch (const UsageError& e) {
    EXPECT_NE(std::string(e.what()).find("sigma-step"), std::string::npos) << "lists the names: " << e.what();
  }
}

TEST(DepthOptionTableTest, ReconstructsFlagsAreTheTables) {
  const auto help = testing::run_cli("reconstruct --help");
  ASSERT_EQ(help.exit_code, 0) << help.output;
  std::set<std::string> names;
  for (const auto& spec : depth_option_table()) {
    EXPECT_TRUE(names.insert(spec.name).second) << spec.name << " twice";
    EXPECT_NE(help.output.find(std::string("--") + spec.name), std::string::npos) << spec.name;
  }
  const auto refused = testing::run_cli("reconstruct T.h5 --calib rig.yaml -o out --passes 21");
  EXPECT_EQ(refused.exit_code, 2) << refused.output;
}

}  // namespace
}  // namespace rfrecon::depth
