// Fast decoding of the PNGs cameras and OpenCV's imwrite give frames as: grayscale, 8 or 16 bits, not interlaced.
#pragma once

#include <filesystem>
#include <optional>

#include <opencv2/core.hpp>

namespace rfrecon {

// `file` decoded to CV_8UC1 or CV_16UC1, exactly the pixels cv::imread gives with IMREAD_UNCHANGED and with
// IMREAD_GRAYSCALE | IMREAD_ANYDEPTH (tests/core/gray_png_test.cc), faster (half its time on 16-bit frames,
// docs/performance.md): libdeflate inflates the whole image data at once, the rows are unfiltered here. std::nullopt
// where the file is anything else (a colour, palette, alpha, transparency, sub-byte or interlaced PNG, one with EXIF
// orientation) or not a well-formed PNG (a critical chunk's CRC, a stream that does not inflate to the declared rows,
// an unknown filter): those are left to cv::imread, which decodes or refuses them as before. Throws InputError naming
// the file where it cannot be read or is over kMaxGrayPngBytes (host/core/limits.h), read whole.
std::optional<cv::Mat> decode_gray_png(const std::filesystem::path& file);

}  // namespace rfrecon
