// The width and height an image file declares in its header, read without decoding it (PNG, TIFF).
#pragma once

#include <filesystem>
#include <optional>

#include <opencv2/core.hpp>

namespace rfrecon {

// The size in a PNG's IHDR or a TIFF's first directory (ImageWidth, ImageLength); nullopt for other formats or a
// header too damaged to say (the decoder then reports the file).
std::optional<cv::Size> image_header_size(const std::filesystem::path& file);

}  // namespace rfrecon
