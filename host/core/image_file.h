// Image files through OpenCV with rfrecon's rules: TIFFs uncompressed, type-checked reads that name the file.
#pragma once

#include <filesystem>
#include <string>

#include <opencv2/core.hpp>

namespace rfrecon {

// "WxH", as messages and options write image sizes.
std::string size_text(cv::Size size);

// The extension of `file` in lower case, with its dot (".tiff"); "" when it has none.
std::string lowercase_extension(const std::filesystem::path& file);

// cv::imwrite by extension; TIFFs are written uncompressed (OpenCV 4.6 corrupts multi-channel float TIFFs with its
// default LZW, and camera frames decode at memory speed uncompressed). Not atomic by itself: write into a
// StagingDirectory or AtomicFile temporary. Throws OutputError naming the file when it cannot be written.
void write_image(const std::filesystem::path& file, const cv::Mat& image);

// cv::imread(file, flags) with the checks every image read needs, before anything is decoded: a regular file (a
// FIFO is refused without opening it), a format of read_image_header (PNG, TIFF, JPEG, BMP, PNM), the size its
// header declares within host/core/limits.h, a file large enough for the data it declares and memory for the
// decoded pixels. Every failure, the decoder's included, is an InputError naming the file. Never returns an empty
// image. Grey 8- and 16-bit PNGs, read unchanged or as IMREAD_GRAYSCALE | IMREAD_ANYDEPTH, take the faster
// decode_gray_png (host/core/gray_png.h) to the same pixels.
cv::Mat decode_image(const std::filesystem::path& file, int flags);

// Reads `file` unchanged and checks that it holds `type` (e.g. CV_32FC3). Throws InputError naming the file when
// it is missing, cannot be decoded or has another type.
cv::Mat read_image(const std::filesystem::path& file, int type);

}  // namespace rfrecon
