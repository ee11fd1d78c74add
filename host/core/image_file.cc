// Checked image reads and writes over cv::imread / cv::imwrite.
#include "host/core/image_file.h"

#include <stdexcept>
#include <string>
#include <vector>

#include <opencv2/imgcodecs.hpp>

#include "host/core/errors.h"

namespace rfrecon {

std::string size_text(cv::Size size) { return std::to_string(size.width) + "x" + std::to_string(size.height); }

void write_image(const std::filesystem::path& file, const cv::Mat& image) {
  const std::vector<int> uncompressed{cv::IMWRITE_TIFF_COMPRESSION, 1};
  if (!cv::imwrite(file.string(), image, image.depth() == CV_32F ? uncompressed : std::vector<int>{})) {
    throw std::runtime_error("cannot write " + file.string());
  }
}

cv::Mat read_image(const std::filesystem::path& file, int type) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(file, ec)) throw InputError(file.string() + ": missing");
  cv::Mat image = cv::imread(file.string(), cv::IMREAD_UNCHANGED);
  if (image.empty()) throw InputError(file.string() + ": cannot be read as an image");
  if (image.type() != type) {
    throw InputError(file.string() + ": holds " + cv::typeToString(image.type()) + " pixels, expected " +
                     cv::typeToString(type));
  }
  return image;
}

}  // namespace rfrecon
