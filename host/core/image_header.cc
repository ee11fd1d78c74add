// PNG IHDR and TIFF IFD0 size fields, so an image's size is checked before OpenCV allocates for it.
#include "host/core/image_header.h"

#include <array>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <limits>

namespace rfrecon {

namespace {
std::uint32_t big_endian(const unsigned char* bytes, int count) {
  std::uint32_t value = 0;
  for (int i = 0; i < count; ++i) value = (value << 8) | bytes[i];
  return value;
}

std::uint32_t little_endian(const unsigned char* bytes, int count) {
  std::uint32_t value = 0;
  for (int i = count - 1; i >= 0; --i) value = (value << 8) | bytes[i];
  return value;
}

std::optional<cv::Size> as_size(std::uint64_t width, std::uint64_t height) {
  const auto clamp = [](std::uint64_t v) {
    return static_cast<int>(std::min<std::uint64_t>(v, std::numeric_limits<int>::max()));
  };
  return cv::Size(clamp(width), clamp(height));
}

std::optional<cv::Size> png_size(std::ifstream& in) {
  std::array<unsigned char, 24> header{};
  if (!in.read(reinterpret_cast<char*>(header.data()), header.size())) return std::nullopt;
  if (std::memcmp(header.data() + 12, "IHDR", 4) != 0) return std::nullopt;
  return as_size(big_endian(header.data() + 16, 4), big_endian(header.data() + 20, 4));
}

// Classic TIFF: the first IFD's ImageWidth (256) and ImageLength (257), SHORT or LONG.
std::optional<cv::Size> tiff_size(std::ifstream& in, bool little) {
  const auto read = [&](std::uint64_t offset, int count) -> std::optional<std::uint32_t> {
    std::array<unsigned char, 4> bytes{};
    in.clear();
    in.seekg(static_cast<std::streamoff>(offset));
    if (!in.read(reinterpret_cast<char*>(bytes.data()), count)) return std::nullopt;
    return little ? little_endian(bytes.data(), count) : big_endian(bytes.data(), count);
  };
  const auto ifd = read(4, 4);
  const auto entries = ifd ? read(*ifd, 2) : std::nullopt;
  if (!entries) return std::nullopt;
  std::uint64_t width = 0;
  std::uint64_t height = 0;
  for (std::uint32_t i = 0; i < *entries && i < 4096; ++i) {
    const std::uint64_t entry = *ifd + 2 + 12ULL * i;
    const auto tag = read(entry, 2);
    const auto type = read(entry + 2, 2);
    if (!tag || !type) return std::nullopt;
    if (*tag != 256 && *tag != 257) continue;
    const auto value = read(entry + 8, *type == 3 ? 2 : 4);
    if (!value) return std::nullopt;
    (*tag == 256 ? width : height) = *value;
  }
  if (width == 0 && height == 0) return std::nullopt;
  return as_size(width, height);
}
}  // namespace

std::optional<cv::Size> image_header_size(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  std::array<unsigned char, 4> magic{};
  if (!in.read(reinterpret_cast<char*>(magic.data()), magic.size())) return std::nullopt;
  in.seekg(0);
  if (std::memcmp(magic.data(), "\x89PNG", 4) == 0) return png_size(in);
  if (std::memcmp(magic.data(), "II*\0", 4) == 0) return tiff_size(in, true);
  if (std::memcmp(magic.data(), "MM\0*", 4) == 0) return tiff_size(in, false);
  return std::nullopt;
}

}  // namespace rfrecon
