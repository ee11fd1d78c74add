// Image reads check the header (format, declared size, data that fits the file) before decoding, refuse non-regular
// files without opening them, and report every failure as an InputError naming the file.
#include "host/core/image_file.h"

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <opencv2/imgcodecs.hpp>
#include <sys/stat.h>

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

bool contains(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

// Overwrites `count` bytes of `file` at `offset` with `value`, big- or little-endian.
void patch(const fs::path& file, std::streamoff offset, std::uint32_t value, bool big_endian, int count = 4) {
  std::fstream io(file, std::ios::in | std::ios::out | std::ios::binary);
  io.seekp(offset);
  for (int i = 0; i < count; ++i) {
    const int shift = 8 * (big_endian ? count - 1 - i : i);
    io.put(static_cast<char>((value >> shift) & 0xffu));
  }
}

void write_text(const fs::path& file, const std::string& text) { std::ofstream(file, std::ios::binary) << text; }

// The offset of the first occurrence of `bytes` in `file` (e.g. a JPEG marker).
std::streamoff find_bytes(const fs::path& file, const std::string& bytes) {
  std::ifstream in(file, std::ios::binary);
  const std::string content((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const auto offset = content.find(bytes);
  EXPECT_NE(offset, std::string::npos) << file;
  return static_cast<std::streamoff>(offset);
}

// The offset of the value of a little-endian TIFF's entry `tag`, a SHORT of count 1 (as OpenCV writes sizes).
std::streamoff tiff_short_value(const fs::path& file, std::uint16_t tag) {
  const char entry[6] = {static_cast<char>(tag & 0xff), static_cast<char>(tag >> 8), 3, 0, 1, 0};
  return find_bytes(file, std::string(entry, 6)) + 8;
}

class ImageFileTest : public ::testing::Test {
 protected:
  // A 64x48 8-bit image written with `extension`, TIFFs uncompressed.
  fs::path written(const std::string& name, const cv::Mat& image = cv::Mat(48, 64, CV_8U, cv::Scalar(90))) const {
    const fs::path file = dir_ / name;
    cv::imwrite(file.string(), image, {cv::IMWRITE_TIFF_COMPRESSION, 1});
    return file;
  }

  testing::TempDir temp_{"image_file"};
  const fs::path dir_ = temp_.path();
};

TEST_F(ImageFileTest, TiffsAreWrittenUncompressed) {
  // A constant image, which any compression would shrink, keeps every sample's bytes: tag 259 (Compression) is 1.
  for (const int type : {CV_8UC1, CV_16UC1, CV_32FC1}) {
    const cv::Mat image(48, 64, type, cv::Scalar(7));
    const fs::path file = dir_ / ("constant_" + std::to_string(type) + ".tiff");
    write_image(file, image);
    EXPECT_GE(fs::file_size(file), image.total() * image.elemSize()) << file;
    std::ifstream in(file, std::ios::binary);
    in.seekg(tiff_short_value(file, 259));
    EXPECT_EQ(in.get(), 1) << file;
    EXPECT_EQ(cv::norm(read_image(file, type), image, cv::NORM_INF), 0.0) << file;
  }
}

TEST_F(ImageFileTest, EveryFormatsHeaderIsReadWithoutDecoding) {
  const cv::Mat deep(48, 64, CV_16U, cv::Scalar(1000));
  const cv::Mat color(48, 64, CV_8UC3, cv::Scalar(10, 20, 30));
  const std::vector<std::pair<fs::path, std::string>> files{
      {written("a.png", deep), "PNG"}, {written("a.tif", deep), "TIFF"}, {written("a.jpg"), "JPEG"},
      {written("a.bmp"), "BMP"},       {written("a.pgm", deep), "PNM"},  {written("a.ppm", color), "PNM"}};
  for (const auto& [file, format] : files) {
    const ImageHeader header = read_image_header(file);
    EXPECT_EQ(header.format, format) << file;
    EXPECT_EQ(header.width, 64) << file;
    EXPECT_EQ(header.height, 48) << file;
    EXPECT_LE(header.min_file_bytes, fs::file_size(file)) << file;
    EXPECT_EQ(decode_image(file, cv::IMREAD_UNCHANGED).size(), cv::Size(64, 48)) << file;
  }
  EXPECT_EQ(read_image_header(dir_ / "a.tif").bytes_per_sample, 2);
  EXPECT_EQ(read_image_header(dir_ / "a.pgm").bytes_per_sample, 2);
  EXPECT_EQ(read_image_header(dir_ / "a.ppm").channels, 3);
}

// stat(2) alone decides: opening a FIFO with no writer would wait forever.
TEST_F(ImageFileTest, AFifoIsRefusedWithoutOpeningIt) {
  const fs::path fifo = dir_ / "frame.png";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  const std::string message = error_of(fifo);
  EXPECT_TRUE(contains(message, fifo.string())) << message;
  EXPECT_TRUE(contains(message, "FIFO")) << message;
}

TEST_F(ImageFileTest, AHugeDeclaredSizeIsRefusedBeforeDecodingNamingTheLimit) {
  const fs::path png = written("huge.png");
  patch(png, 16, 100000, true);  // IHDR width
  const fs::path bmp = written("huge.bmp");
  patch(bmp, 22, 100000, false);  // biHeight
  const fs::path jpeg = written("huge.jpg");
  patch(jpeg, find_bytes(jpeg, "\xFF\xC0") + 5, 60000, true, 2);  // SOF0 height
  const fs::path pgm = dir_ / "huge.pgm";
  write_text(pgm, "P5\n100000 48\n255\n" + std::string(64, '\0'));
  const fs::path tiff = written("huge.tif");
  patch(tiff, tiff_short_value(tiff, 256), 20000, false, 2);  // ImageWidth
  for (const fs::path& file : {png, bmp, jpeg, pgm, tiff}) {
    const std::string message = error_of(file);
    EXPECT_TRUE(contains(message, file.string())) << message;
    EXPECT_TRUE(contains(message, "over the limit (at most 16384 px a side")) << message;
  }
}

// Within the limits but more data than the file can hold: refused before OpenCV allocates the image.
TEST_F(ImageFileTest, DeclaredDataThatCannotFitTheFileIsRefused) {
  const fs::path pgm = dir_ / "small.pgm";  // 8192 x 8192 16-bit samples: 128 MiB, in 200 bytes
  const std::string header = "P5\n8192 8192\n65535\n";
  write_text(pgm, header + std::string(200 - header.size(), '\x01'));
  const fs::path png = written("small.png");
  patch(png, 16, 8192, true);
  patch(png, 20, 8192, true);                 // 64 MiB of rows: at least 65 kB of deflate data
  const fs::path tiff = written("tall.tif");  // uncompressed 64 x 4000: 256 kB
  patch(tiff, tiff_short_value(tiff, 257), 4000, false, 2);
  const fs::path bmp = written("truncated.bmp");
  fs::resize_file(bmp, fs::file_size(bmp) - 100);
  const fs::path jpeg = written("small.jpg");
  patch(jpeg, find_bytes(jpeg, "\xFF\xC0") + 5, 8192, true, 2);  // 8192 x 64: 8192 blocks, at least 2 kB
  patch(jpeg, find_bytes(jpeg, "\xFF\xC0") + 7, 8192, true, 2);
  for (const fs::path& file : {pgm, png, tiff, bmp, jpeg}) {
    const std::string message = error_of(file);
    EXPECT_TRUE(contains(message, file.string())) << message;
    EXPECT_TRUE(contains(message, "bytes, the file has")) << message;
  }
  EXPECT_TRUE(contains(error_of(pgm), "a 8192x8192 PNM needs at least 134217747 bytes, the file has 200"));
}

TEST_F(ImageFileTest, TruncatedOrImpossibleHeadersAreRefusedNamingTheFile) {
  const fs::path short_png = written("short.png");
  fs::resize_file(short_png, 20);
  write_text(dir_ / "pam.pgm", "P7\nWIDTH 4\nHEIGHT 4\nDEPTH 1\nMAXVAL 255\nENDHDR\n" + std::string(16, '\0'));
  write_text(dir_ / "digits.pgm", "P5\n12345678901 1\n255\n");
  write_text(dir_ / "comment.pgm", "P5\n# a comment that never ends");
  write_text(dir_ / "no_frame.jpg", std::string("\xFF\xD8\xFF\xDA\x00\x02", 6));
  write_text(dir_ / "garbage.png", "not an image");
  for (const auto& [name, needle] :
       std::vector<std::pair<std::string, std::string>>{{"short.png", "PNG header is truncated"},
                                                        {"pam.pgm", "not an image rfrecon reads"},
                                                        {"digits.pgm", "longer than 10 digits"},
                                                        {"comment.pgm", "PNM header is truncated"},
                                                        {"no_frame.jpg", "JPEG without a frame header"},
                                                        {"garbage.png", "not an image rfrecon reads"}}) {
    const std::string message = error_of(dir_ / name);
    EXPECT_TRUE(contains(message, (dir_ / name).string())) << message;
    EXPECT_TRUE(contains(message, needle)) << message;
  }
}

TEST_F(ImageFileTest, ATiffOfMoreThanFourSamplesPerPixelIsRefused) {
  const fs::path file = written("five.tif");
  patch(file, tiff_short_value(file, 277), 5, false, 2);  // SamplesPerPixel
  const std::string message = error_of(file);
  EXPECT_TRUE(contains(message, file.string()) && contains(message, "5 samples per pixel (rfrecon reads 1 to 4)"))
      << message;
}

TEST_F(ImageFileTest, MissingFilesAndDirectoriesAreRefusedByName) {
  fs::create_directory(dir_ / "folder.png");
  for (const auto& [file, needle] : std::vector<std::pair<fs::path, std::string>>{
           {dir_ / "missing.png", "missing"}, {dir_ / "folder.png", "is a directory"}}) {
    const std::string message = error_of(file);
    EXPECT_TRUE(contains(message, file.string())) << message;
    EXPECT_TRUE(contains(message, needle)) << message;
  }
}

}  // namespace
}  // namespace rfrecon
