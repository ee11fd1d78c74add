// decode_gray_png gives back exactly the pixels written, as cv::imread (libpng) reads them, for every PNG row filter,
// both bit depths and widths that do not fill its 8-byte steps; every other PNG is left to cv::imread.
#include "host/core/gray_png.h"

#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <libdeflate.h>
#include <opencv2/imgcodecs.hpp>

#include "host/core/errors.h"
#include "host/core/image_file.h"
#include "tests/common/temp_dir.h"

namespace rfrecon {
namespace {

namespace fs = std::filesystem;
using Bytes = std::vector<unsigned char>;

void put_32(Bytes& bytes, std::uint32_t value) {
  for (int shift = 24; shift >= 0; shift -= 8) bytes.push_back(static_cast<unsigned char>(value >> shift));
}

void put_chunk(Bytes& png, const std::string& type, const Bytes& data) {
  put_32(png, static_cast<std::uint32_t>(data.size()));
  Bytes typed(type.begin(), type.end());
  typed.insert(typed.end(), data.begin(), data.end());
  png.insert(png.end(), typed.begin(), typed.end());
  put_32(png, libdeflate_crc32(0, typed.data(), typed.size()));
}

// Row y of `image` as PNG stores it (big-endian samples) with filter `filter` (PNG specification, section 9).
Bytes filtered_row(const cv::Mat& image, int y, int filter) {
  const std::size_t bpp = image.elemSize();
  const auto bytes_of = [&](int row) {
    Bytes raw(image.cols * bpp, 0);
    if (row < 0) return raw;
    for (int x = 0; x < image.cols; ++x) {
      const unsigned value = bpp == 1 ? image.at<std::uint8_t>(row, x) : image.at<std::uint16_t>(row, x);
      if (bpp == 2) raw[2 * x] = static_cast<unsigned char>(value >> 8);
      raw[bpp * x + bpp - 1] = static_cast<unsigned char>(value & 0xffu);
    }
    return raw;
  };
  const Bytes row = bytes_of(y), above = bytes_of(y - 1);
  Bytes out{static_cast<unsigned char>(filter)};
  for (std::size_t i = 0; i < row.size(); ++i) {
    const int a = i >= bpp ? row[i - bpp] : 0, b = above[i], c = i >= bpp ? above[i - bpp] : 0;
    const int pa = std::abs(b - c), pb = std::abs(a - c), pc = std::abs(a + b - 2 * c);
    const int predictor[] = {0, a, b, (a + b) / 2, pa <= pb && pa <= pc ? a : pb <= pc ? b : c};
    out.push_back(static_cast<unsigned char>(row[i] - (filter <= 4 ? predictor[filter] : 0)));
  }
  return out;
}

struct PngOptions {
  int filter = -1;         // every row's filter; -1: row y takes filter y % 5
  std::size_t chunk = 97;  // bytes per IDAT chunk
  std::uint8_t colour_type = 0;
  std::uint8_t interlace = 0;
  std::vector<std::string> extra_chunks;  // empty chunks written after IHDR
};

// A PNG of `image` (CV_8UC1 or CV_16UC1), written here rather than by libpng so that every filter is used.
Bytes encode_png(const cv::Mat& image, const PngOptions& options = {}) {
  Bytes filtered;
  for (int y = 0; y < image.rows; ++y) {
    const Bytes row = filtered_row(image, y, options.filter >= 0 ? options.filter : y % 5);
    filtered.insert(filtered.end(), row.begin(), row.end());
  }
  libdeflate_compressor* compressor = libdeflate_alloc_compressor(6);
  Bytes compressed(libdeflate_zlib_compress_bound(compressor, filtered.size()));
  compressed.resize(
      libdeflate_zlib_compress(compressor, filtered.data(), filtered.size(), compressed.data(), compressed.size()));
  libdeflate_free_compressor(compressor);
  Bytes png{0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
  Bytes header;
  put_32(header, static_cast<std::uint32_t>(image.cols));
  put_32(header, static_cast<std::uint32_t>(image.rows));
  header.insert(header.end(),
                {static_cast<unsigned char>(8 * image.elemSize()), options.colour_type, 0, 0, options.interlace});
  put_chunk(png, "IHDR", header);
  for (const std::string& type : options.extra_chunks) put_chunk(png, type, type == "PLTE" ? Bytes(3, 0) : Bytes{});
  for (std::size_t at = 0; at < compressed.size(); at += options.chunk) {
    put_chunk(png, "IDAT",
              Bytes(compressed.begin() + at, compressed.begin() + std::min(at + options.chunk, compressed.size())));
  }
  put_chunk(png, "IEND", {});
  return png;
}

PngOptions with_filter(int filter, std::size_t chunk = 97) {
  PngOptions options;
  options.filter = filter;
  options.chunk = chunk;
  return options;
}

fs::path write_file(const fs::path& file, const Bytes& bytes) {
  std::ofstream(file, std::ios::binary).write(reinterpret_cast<const char*>(bytes.data()), bytes.size());
  return file;
}

cv::Mat random_image(int width, int height, int type, int seed) {
  cv::Mat image(height, width, type);
  cv::RNG(seed).fill(image, cv::RNG::UNIFORM, 0, type == CV_8UC1 ? 256 : 65536);
  return image;
}

bool same(const cv::Mat& a, const cv::Mat& b) {
  return a.type() == b.type() && a.size() == b.size() && cv::norm(a, b, cv::NORM_INF) == 0;
}

TEST(GrayPng, EveryFilterBitDepthAndWidthGivesBackThePixelsAsLibpngDoes) {
  testing::TempDir dir("gray_png");
  for (const int type : {CV_8UC1, CV_16UC1}) {
    for (const int width : {1, 3, 4, 7, 9, 33}) {
      for (const int filter : {-1, 0, 1, 2, 3, 4}) {
        SCOPED_TRACE("type " + cv::typeToString(type) + ", width " + std::to_string(width) + ", filter " +
                     std::to_string(filter));
        const cv::Mat image = random_image(width, 11, type, 100 * width + filter);
        const fs::path file = write_file(dir.path() / "frame.png", encode_png(image, with_filter(filter)));
        const std::optional<cv::Mat> decoded = decode_gray_png(file);
        ASSERT_TRUE(decoded.has_value());
        EXPECT_TRUE(same(*decoded, image));
        EXPECT_TRUE(same(*decoded, cv::imread(file.string(), cv::IMREAD_UNCHANGED)));
      }
    }
  }
}

TEST(GrayPng, OpenCvsOwnPngsDecodeToTheirPixels) {
  testing::TempDir dir("gray_png");
  for (const int type : {CV_8UC1, CV_16UC1}) {
    for (const int level : {0, 1, 3, 9}) {
      for (const int strategy :
           {cv::IMWRITE_PNG_STRATEGY_DEFAULT, cv::IMWRITE_PNG_STRATEGY_FILTERED, cv::IMWRITE_PNG_STRATEGY_RLE}) {
        // Smooth with noise, as camera frames are, so that libpng's adaptive filtering picks several filters.
        cv::Mat image = random_image(641, 37, type, level);
        cv::Mat ramp(image.size(), CV_32F);
        for (int y = 0; y < ramp.rows; ++y) {
          for (int x = 0; x < ramp.cols; ++x) ramp.at<float>(y, x) = static_cast<float>(40 * x + 300 * y);
        }
        cv::Mat smooth;
        ramp.convertTo(smooth, type, type == CV_8UC1 ? 1.0 / 256 : 1.0);
        image = smooth + (image & (type == CV_8UC1 ? 3 : 63));
        const fs::path file = dir.path() / "frame.png";
        ASSERT_TRUE(cv::imwrite(file.string(), image,
                                {cv::IMWRITE_PNG_COMPRESSION, level, cv::IMWRITE_PNG_STRATEGY, strategy}));
        const std::optional<cv::Mat> decoded = decode_gray_png(file);
        ASSERT_TRUE(decoded.has_value()) << "level " << level << ", strategy " << strategy;
        EXPECT_TRUE(same(*decoded, image)) << "level " << level << ", strategy " << strategy;
      }
    }
  }
}

TEST(GrayPng, LeavesEveryOtherPngToOpenCv) {
  testing::TempDir dir("gray_png");
  const cv::Mat gray = random_image(8, 6, CV_8UC1, 7);
  const auto declined = [&](const std::string& name, const Bytes& bytes) {
    return !decode_gray_png(write_file(dir.path() / (name + ".png"), bytes)).has_value();
  };
  cv::Mat colour(6, 8, CV_8UC3, cv::Scalar(10, 20, 30));
  ASSERT_TRUE(cv::imwrite((dir.path() / "colour.png").string(), colour));
  EXPECT_FALSE(decode_gray_png(dir.path() / "colour.png").has_value());
  PngOptions interlaced;
  interlaced.interlace = 1;
  EXPECT_TRUE(declined("interlaced", encode_png(gray, interlaced)));
  for (const char* chunk : {"tRNS", "eXIf", "PLTE", "ABCD"}) {
    PngOptions extra;
    extra.extra_chunks = {chunk};
    EXPECT_TRUE(declined(chunk, encode_png(gray, extra))) << chunk;
  }
  PngOptions ancillary;
  ancillary.extra_chunks = {"tEXt", "gAMA"};
  EXPECT_FALSE(declined("ancillary", encode_png(gray, ancillary)));

  const Bytes good = encode_png(gray);
  Bytes bad_crc = good;
  bad_crc[8 + 25 + 8 + 3] ^= 1u;  // first IDAT chunk's data, its CRC left as it was
  EXPECT_TRUE(declined("bad_crc", bad_crc));
  EXPECT_TRUE(declined("truncated", Bytes(good.begin(), good.end() - 20)));
  EXPECT_TRUE(declined("bad_filter", encode_png(gray, with_filter(5))));  // no such filter type
}

TEST(GrayPng, DecodeImageStillRefusesADamagedGreyPngNamingIt) {
  testing::TempDir dir("gray_png");
  Bytes bytes = encode_png(random_image(64, 64, CV_16UC1, 3), with_filter(1, 1u << 20));
  for (std::size_t i = 8 + 25 + 8 + 2; i < bytes.size() - 16; ++i) bytes[i] = 0xff;  // the deflate stream
  const fs::path file = write_file(dir.path() / "damaged.png", bytes);
  try {
    (void)decode_image(file, cv::IMREAD_UNCHANGED);
    FAIL() << "no InputError";
  } catch (const InputError& error) {
    EXPECT_NE(std::string(error.what()).find(file.string()), std::string::npos) << error.what();
  }
}

}  // namespace
}  // namespace rfrecon
