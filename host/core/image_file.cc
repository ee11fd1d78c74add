// Checked image reads and writes over cv::imread / cv::imwrite.
#include "host/core/image_file.h"

#include <algorithm>
#include <cctype>
#include <stdexcept>
#include <string>
#include <vector>

#include <opencv2/imgcodecs.hpp>

#include "host/core/errors.h"
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
  const std::vector<int> uncompressed{cv::IMWRITE_TIFF_COMPRESSION, 1};
  if (!cv::imwrite(file.string(), image, image.depth() == CV_32F ? uncompressed : std::vector<int>{})) {
    throw OutputError("cannot write " + file.string() + " (permission, read-only file system or disk full)");
  }
}

cv::Mat decode_image(const std::filesystem::path& file, int flags) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(file, ec)) {
    throw InputError(file.string() + (std::filesystem::exists(file, ec) ? ": not a regular file" : ": missing"));
  }
  if (const auto size = image_header_size(file)) check_image_size(*size, file.string());
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
