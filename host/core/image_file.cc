// Checked image reads and writes over cv::imread / cv::imwrite, grey PNGs decoded by host/core/gray_png.h.
#include "host/core/image_file.h"

#include <algorithm>
#include <cctype>
#include <climits>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include <opencv2/imgcodecs.hpp>

#include "host/core/errors.h"
#include "host/core/gray_png.h"
#include "host/core/image_header.h"
#include "host/core/limits.h"

namespace rfrecon {

std::string size_text(cv::Size size) { return std::to_string(size.width) + "x" + std::to_string(size.height); }

std::string lowercase_extension(const std::filesystem::path& file) {
  std::string extension = file.extension().string();
  std::transform(extension.begin(), extension.end(), extension.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return extension;
}

void write_image(const std::filesystem::path& file, const cv::Mat& image) {
  // TIFFs uncompressed: OpenCV's default LZW corrupts multi-channel float TIFFs (4.6), and camera frames decode at
  // memory speed without it (docs/performance.md).
  if (!cv::imwrite(file.string(), image, {cv::IMWRITE_TIFF_COMPRESSION, 1})) {
    throw OutputError("cannot write " + file.string() + " (permission, read-only file system or disk full)");
  }
}

namespace {
// The declared size within host/core/limits.h, the data able to fit in the file, the decoded pixels in memory.
void check_image_header(const ImageHeader& header, const std::filesystem::path& file) {
  const auto clamped = [](std::int64_t side) { return static_cast<int>(std::min<std::int64_t>(side, INT_MAX)); };
  const cv::Size size(clamped(header.width), clamped(header.height));
  check_image_size(size, file.string());
  std::error_code error;
  const std::uintmax_t file_bytes = std::filesystem::file_size(file, error);
  if (error) throw InputError(file.string() + ": cannot be read (" + error.message() + ")");
  if (header.min_file_bytes > file_bytes) {
    throw InputError(file.string() + ": a " + size_text(size) + " " + header.format + " needs at least " +
                     std::to_string(header.min_file_bytes) + " bytes, the file has " + std::to_string(file_bytes) +
                     " (truncated or damaged)");
  }
  check_memory(static_cast<double>(size.area()) * header.channels * header.bytes_per_sample,
               file.string() + ": decoding its " + size_text(size) + " pixels");
}
}  // namespace

cv::Mat decode_image(const std::filesystem::path& file, int flags) {
  const ImageHeader header = read_image_header(file);
  check_image_header(header, file);
  // Grey PNGs (camera frames) the fast way where cv::imread would return them unchanged.
  if (header.format == "PNG" && header.channels == 1 &&
      (flags == cv::IMREAD_UNCHANGED || flags == (cv::IMREAD_GRAYSCALE | cv::IMREAD_ANYDEPTH))) {
    if (std::optional<cv::Mat> image = decode_gray_png(file)) return *std::move(image);
  }
  cv::Mat image;
  try {
    image = cv::imread(file.string(), flags);
  } catch (const cv::Exception& error) {
    throw InputError(file.string() + ": cannot be decoded (" + error.err + ")");
  }
  if (image.empty()) throw InputError(file.string() + ": cannot be read as an image (unreadable or not an image)");
  return image;
}

cv::Mat read_image(const std::filesystem::path& file, int type) {
  cv::Mat image = decode_image(file, cv::IMREAD_UNCHANGED);
  if (image.type() != type) {
    throw InputError(file.string() + ": holds " + cv::typeToString(image.type()) + " pixels, expected " +
                     cv::typeToString(type));
  }
  return image;
}

}  // namespace rfrecon
