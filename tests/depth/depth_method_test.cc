// The depth-method registry: the built-ins in order, a name taken twice refused, an unknown name an InputError that
// lists the known ones.
#include "host/depth/depth_method.h"

#include <stdexcept>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "host/core/errors.h"

namespace rfrecon::depth {
namespace {

using ::testing::HasSubstr;

class NamedMethod : public DepthMethod {
 public:
  explicit NamedMethod(std::string name) : name_(std::move(name)) {}
  std::string name() const override { return name_; }
  std::string description() const override { return "test"; }
  bool needs_rows() const override { return false; }
  std::vector<cl::ProgramRequest> programs(const transport::CompressedTransport&) const override { return {}; }
  cv::Mat solve(MethodScan& scan) const override { return scan.triangulation.z_rect_mm; }

 private:
  std::string name_;
};

TEST(DepthMethodRegistry, BuiltInsComeFirstAndKnowWhatTheyNeed) {
  const auto names = depth_method_names();
  ASSERT_GE(names.size(), 3u);
  EXPECT_EQ(std::vector<std::string>(names.begin(), names.begin() + 3),
            (std::vector<std::string>{"triangulate", "integrate", "fused"}));
  EXPECT_FALSE(depth_method("triangulate").needs_rows());
  EXPECT_TRUE(depth_method("integrate").needs_rows());
  EXPECT_TRUE(depth_method("fused").needs_rows());
}

TEST(DepthMethodRegistry, ANameTakenTwiceIsRefusedAndAnUnknownOneListsTheKnown) {
  register_depth_method(std::make_shared<const NamedMethod>("registry-test"));
  EXPECT_EQ(depth_method("registry-test").name(), "registry-test");
  EXPECT_THROW(register_depth_method(std::make_shared<const NamedMethod>("fused")), std::invalid_argument);
  try {
    (void)depth_method("no-such-method");
    ADD_FAILURE() << "an unknown method was found";
  } catch (const InputError& error) {
    EXPECT_THAT(error.what(), HasSubstr("'no-such-method' (triangulate, integrate, fused, registry-test)"));
  }
}

}  // namespace
}  // namespace rfrecon::depth
