// Image reads check the size a PNG or TIFF header declares before decoding, and report every failure as an
// InputError naming the file.
#include "host/core/image_file.h"

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <opencv2/imgcodecs.hpp>

#include "host/core/errors.h"
#include "host/core/image_header.h"
#include "tests/common/temp_dir.h"

namespace rfrecon {
namespace {

namespace fs = std::filesystem;

std::string error_of(const fs::path& file) {
  try {
    (void)decode_image(file, cv::IMREAD_UNCHANGED);
  } catch (const InputError& error) {
    return error.what();
  }
  return "(no InputError)";
}

// Overwrites 4 bytes of `file` at `offset`, big- or little-endian.
void patch(const fs::path& file, std::streamoff offset, std::uint32_t value, bool big_endian) {
  std::fstream io(file, std::ios::in | std::ios::out | std::ios::binary);
  io.seekp(offset);
  for (int i = 0; i < 4; ++i) {
    const int shift = big_endian ? 24 - 8 * i : 8 * i;
    io.put(static_cast<char>((value >> shift) & 0xffu));
  }
}

class ImageFileTest : public ::testing::Test {
 protected:
  testing::TempDir temp_{"image_file"};
  const fs::path dir_ = temp_.path();
};

TEST_F(ImageFileTest, HeaderSizesAreReadWithoutDecoding) {
  const cv::Mat image(48, 64, CV_16U, cv::Scalar(1000));
  cv::imwrite((dir_ / "a.png").string(), image);
  cv::imwrite((dir_ / "a.tif").string(), image);
  EXPECT_EQ(image_header_size(dir_ / "a.png"), cv::Size(64, 48));
  EXPECT_EQ(image_header_size(dir_ / "a.tif"), cv::Size(64, 48));
  EXPECT_EQ(decode_image(dir_ / "a.png", cv::IMREAD_UNCHANGED).size(), cv::Size(64, 48));
}

TEST_F(ImageFileTest, AHugeDeclaredSizeIsRefusedBeforeDecoding) {
  cv::imwrite((dir_ / "huge.png").string(), cv::Mat(8, 8, CV_8U, cv::Scalar(7)));
  patch(dir_ / "huge.png", 16, 100000, true);  // IHDR width
  patch(dir_ / "huge.png", 20, 100000, true);  // IHDR height
  const std::string message = error_of(dir_ / "huge.png");
  EXPECT_NE(message.find("huge.png"), std::string::npos) << message;
  EXPECT_NE(message.find("over the limit"), std::string::npos) << message;
}

TEST_F(ImageFileTest, EveryFailureNamesTheFile) {
  std::ofstream(dir_ / "garbage.png") << "not an image";
  fs::create_directory(dir_ / "folder.png");
  for (const auto& [file, needle] :
       std::vector<std::pair<fs::path, std::string>>{{dir_ / "missing.png", "missing"},
                                                     {dir_ / "garbage.png", "cannot be read"},
                                                     {dir_ / "folder.png", "regular"}}) {
    const std::string message = error_of(file);
    EXPECT_NE(message.find(file.string()), std::string::npos) << message;
    EXPECT_NE(message.find(needle), std::string::npos) << message;
  }
}

}  // namespace
}  // namespace rfrecon
