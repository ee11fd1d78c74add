// The JSON and YAML readers refuse by name, before parsing: inputs that are not regular files (without blocking on a
// FIFO), files over their size limit, nesting past kMaxNestingDepth; and quote input text cut to a readable length.
#include <filesystem>
#include <fstream>
#include <string>

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <sys/stat.h>

#include "host/core/errors.h"
#include "host/core/json_file.h"
#include "host/core/limits.h"
#include "host/core/message_text.h"
#include "host/core/opencv_yaml.h"
#include "tests/common/temp_dir.h"
#include "tests/core/refusal_in_child.h"

namespace rfrecon {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;
using ::testing::Not;

class TextLimitsTest : public ::testing::Test {
 protected:
  fs::path write(const std::string& name, const std::string& text) const {
    const fs::path file = dir_ / name;
    std::ofstream(file, std::ios::binary) << text;
    return file;
  }

  static std::string nested_json(int depth) { return std::string(depth, '[') + std::string(depth, ']'); }

  static std::string json_error(const fs::path& file) {
    return rfrecon::testing::refusal_in_child([&] { (void)read_json_file(file); });
  }

  static std::string yaml_error(const fs::path& file) {
    return rfrecon::testing::refusal_in_child([&] { (void)open_opencv_yaml(file); });
  }

  rfrecon::testing::TempDir temp_{"text_limits"};
  const fs::path dir_ = temp_.path();
  const std::string yaml_head_ = "%YAML:1.0\n---\nimage_size: ";
};

TEST_F(TextLimitsTest, FifoIsRefusedByNameWithoutBlocking) {
  const fs::path fifo = dir_ / "scene.json";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  for (const std::string& message : {json_error(fifo), yaml_error(fifo)}) {
    EXPECT_THAT(message, HasSubstr(fifo.string()));
    EXPECT_THAT(message, HasSubstr("FIFO"));
  }
  EXPECT_THAT(json_error(dir_), HasSubstr("a directory"));
}

TEST_F(TextLimitsTest, JsonNestingIsCappedAtTheLimit) {
  EXPECT_NO_THROW((void)read_json_file(write("at_limit.json", nested_json(kMaxNestingDepth))));
  for (const int depth : {kMaxNestingDepth + 1, 50000}) {  // 100 KB of brackets overflowed the stack before
    const fs::path file = write("deep.json", nested_json(depth));
    const std::string message = json_error(file);
    EXPECT_THAT(message, HasSubstr(file.string()));
    EXPECT_THAT(message, HasSubstr("deeper than " + std::to_string(kMaxNestingDepth) + " levels"));
  }
}

TEST_F(TextLimitsTest, FilesOverTheSizeLimitAreRefusedUnread) {
  const fs::path json = dir_ / "huge.json";
  std::ofstream(json).close();
  fs::resize_file(json, kMaxJsonBytes + 1);  // sparse: nothing of it is read
  EXPECT_THAT(json_error(json), HasSubstr("over the limit of " + std::to_string(kMaxJsonBytes)));
  const fs::path yaml = dir_ / "huge.yaml";
  std::ofstream(yaml).close();
  fs::resize_file(yaml, kMaxYamlBytes + 1);
  EXPECT_THAT(yaml_error(yaml), HasSubstr("over the limit of " + std::to_string(kMaxYamlBytes)));
}

TEST_F(TextLimitsTest, ParseErrorsQuoteTheInputCut) {
  const std::string token(100000, 'x');
  for (const std::string& text : {"{\"a\": " + token + "}", "[1e9" + std::string(100000, '9') + "]"}) {
    const std::string message = json_error(write("long.json", text));
    EXPECT_THAT(message, HasSubstr("not valid JSON"));
    EXPECT_LT(message.size(), 400u) << message;  // the file name, nlohmann's words and at most 80 quoted characters
  }
}

TEST_F(TextLimitsTest, YamlNestingIsCappedWhateverOpensIt) {
  const int n = 50000;  // each of these overflowed the stack of OpenCV's parser
  const std::string deep_texts[] = {
      yaml_head_ + std::string(n, '[') + std::string(n, ']') + "\n",
      yaml_head_ + "\n  " + std::string(n, '{') + std::string(n, '}') + "\n",
      yaml_head_ + "\n  " + std::string(n, '-') + " 1\n",
      [&] {
        std::string keys;
        for (int i = 0; i < n / 4; ++i) keys += "a: ";
        return yaml_head_ + "\n  " + keys + "1\n";
      }(),
      // Brackets hidden from a naive count: closers in a string and a comment, openers after a '#' in a flow scalar.
      yaml_head_ + "[ \"" + std::string(n, ']') + "\", b#, " + std::string(n, '[') + std::string(n, ']') + " ]\n",
  };
  for (const auto& text : deep_texts) {
    const fs::path file = write("deep.yaml", text);
    const std::string message = yaml_error(file);
    EXPECT_THAT(message, HasSubstr(file.string()));
    EXPECT_THAT(message, HasSubstr("deeper than " + std::to_string(kMaxNestingDepth) + " levels"));
  }
}

TEST_F(TextLimitsTest, YamlWithinTheLimitOpens) {
  const fs::path file = write("rig.yaml", yaml_head_ +
                                              "[ 640, 480 ]  # [px] [\ncamera_matrix: !!opencv-matrix\n"
                                              "   rows: 1\n   cols: 2\n   dt: d\n   data: [ -1.5e-02,\n"
                                              "       -2. ]\nlabel: \"a ] b\"\n");
  const cv::FileStorage storage = open_opencv_yaml(file);
  EXPECT_EQ(static_cast<int>(storage["image_size"][1]), 480);
  EXPECT_EQ(static_cast<std::string>(storage["label"]), "a ] b");
}

TEST_F(TextLimitsTest, ExcerptBoundsAQuote) {
  const std::string quoted = excerpt(std::string(100000, 'k'));
  EXPECT_LE(quoted.size(), kMaxQuotedChars + 30);
  EXPECT_THAT(quoted, HasSubstr("100000 bytes"));
  EXPECT_THAT(excerpt("short"), Not(HasSubstr("bytes")));
}

}  // namespace
}  // namespace rfrecon
