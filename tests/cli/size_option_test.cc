// "WxH" command-line sizes: accepted forms and rejected ones.
#include "host/cli/size_option.h"

#include <gtest/gtest.h>

#include "host/core/errors.h"

namespace rfrecon::cli {
namespace {

TEST(SizeOptionTest, ParsesWidthByHeight) {
  EXPECT_EQ(parse_size("1024x768", "--projector"), cv::Size(1024, 768));
  EXPECT_EQ(parse_size("640X480", "--camera"), cv::Size(640, 480));
}

TEST(SizeOptionTest, RejectsAnythingElse) {
  for (const char* bad : {"", "x5", "10x", "0x5", "-3x4", "12ax3", "1234567x2", "10x10x", " 10x10", "10*10",
                          "100000x100000", "16385x2"}) {
    EXPECT_THROW((void)parse_size(bad, "--camera"), UsageError) << "'" << bad << "'";
  }
  EXPECT_EQ(parse_size("16384x2", "--camera"), cv::Size(16384, 2));  // the stated limit, host/core/limits.h
}

}  // namespace
}  // namespace rfrecon::cli
