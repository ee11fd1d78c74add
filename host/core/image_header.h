// What an image file's header declares (PNG, TIFF, JPEG, BMP, PNM), read without decoding it.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>

namespace rfrecon {

struct ImageHeader {
  std::string format;        // "PNG", "TIFF", "JPEG", "BMP" or "PNM"
  std::int64_t width = 0;    // px, as declared
  std::int64_t height = 0;   // px, as declared (a bottom-up BMP's negative height made positive)
  int channels = 1;          // samples per pixel as the decoder returns them unchanged (a palette: 3)
  int bytes_per_sample = 1;  // as the decoder returns them (1, 2, 4 or 8)
  // The fewest bytes a file can have and hold the declared pixels: the exact data size for uncompressed data, that
  // size over the coding's largest ratio (deflate 1032, LZW 4096, PackBits 64, baseline JPEG 2 bits per 8x8 block),
  // 0 where the coding has no such bound (progressive JPEG, RLE BMP, other TIFF codings).
  std::uint64_t min_file_bytes = 0;
};

// Reads `file`'s header: the formats of docs/formats.md#images that rfrecon reads, recognised by content as OpenCV
// does (the first directory of a TIFF, which is the page cv::imread decodes). Throws InputError naming the file when
// it is not a regular file (checked before opening, so a FIFO never blocks), is another format, or its header is
// truncated or impossible (a TIFF with more than 4 samples per pixel, a JPEG with no frame header).
ImageHeader read_image_header(const std::filesystem::path& file);

}  // namespace rfrecon
