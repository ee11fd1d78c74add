// Test helper: reads a float32 TIFF with libtiff itself, as a reader other than OpenCV (PIL, tifffile, MATLAB) sees
// it: samples in file order, so a test can check which quantity each channel of a file holds.
#pragma once

#include <cstdint>
#include <filesystem>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include <tiffio.h>

namespace rfrecon::testing {

struct TiffSamples {
  std::uint32_t width = 0;
  std::uint32_t height = 0;
  int samples = 0;            // per pixel
  std::vector<float> values;  // row-major, the samples of a pixel together, in file order
  float at(std::uint32_t x, std::uint32_t y, int sample) const {
    return values[(static_cast<std::size_t>(y) * width + x) * static_cast<std::size_t>(samples) + sample];
  }
};

// Throws std::runtime_error unless the file holds contiguous 32-bit IEEE float samples.
inline TiffSamples read_float_tiff(const std::filesystem::path& file) {
  const std::unique_ptr<TIFF, void (*)(TIFF*)> tiff(TIFFOpen(file.c_str(), "r"), TIFFClose);
  if (!tiff) throw std::runtime_error("libtiff cannot open " + file.string());
  std::uint16_t samples = 0, bits = 0, format = 0, planar = 0;
  TiffSamples image;
  TIFFGetField(tiff.get(), TIFFTAG_IMAGEWIDTH, &image.width);
  TIFFGetField(tiff.get(), TIFFTAG_IMAGELENGTH, &image.height);
  TIFFGetFieldDefaulted(tiff.get(), TIFFTAG_SAMPLESPERPIXEL, &samples);
  TIFFGetFieldDefaulted(tiff.get(), TIFFTAG_BITSPERSAMPLE, &bits);
  TIFFGetFieldDefaulted(tiff.get(), TIFFTAG_SAMPLEFORMAT, &format);
  TIFFGetFieldDefaulted(tiff.get(), TIFFTAG_PLANARCONFIG, &planar);
  if (bits != 32 || format != SAMPLEFORMAT_IEEEFP || planar != PLANARCONFIG_CONTIG) {
    throw std::runtime_error(file.string() + ": not a contiguous float32 TIFF");
  }
  image.samples = samples;
  const std::size_t row_values = static_cast<std::size_t>(image.width) * samples;
  if (static_cast<std::size_t>(TIFFScanlineSize(tiff.get())) != row_values * sizeof(float)) {
    throw std::runtime_error(file.string() + ": unexpected scanline size");
  }
  image.values.resize(row_values * image.height);
  for (std::uint32_t y = 0; y < image.height; ++y) {
    if (TIFFReadScanline(tiff.get(), image.values.data() + y * row_values, y, 0) < 0) {
      throw std::runtime_error(file.string() + ": cannot read row " + std::to_string(y));
    }
  }
  return image;
}

}  // namespace rfrecon::testing
