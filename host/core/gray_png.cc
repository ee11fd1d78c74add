// Grayscale PNG decoding: chunks checked, the image data inflated by libdeflate in one call, rows unfiltered in place.
#include "host/core/gray_png.h"

#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <string>
#include <vector>

#include <libdeflate.h>

#include "host/core/limits.h"

namespace rfrecon {

static_assert(__BYTE_ORDER__ == __ORDER_LITTLE_ENDIAN__, "gray_png: the row filters and byte swaps assume it");

namespace {

std::uint32_t big_endian_32(const unsigned char* bytes) {
  return (std::uint32_t{bytes[0]} << 24) | (std::uint32_t{bytes[1]} << 16) | (std::uint32_t{bytes[2]} << 8) |
         std::uint32_t{bytes[3]};
}

bool is_type(const unsigned char* type, const char* name) { return std::memcmp(type, name, 4) == 0; }

// Eight bytes added lane by lane, modulo 256 each (no carry between lanes).
std::uint64_t add_bytes(std::uint64_t a, std::uint64_t b) {
  constexpr std::uint64_t kHigh = 0x8080808080808080u;
  return ((a & ~kHigh) + (b & ~kHigh)) ^ ((a ^ b) & kHigh);
}

// PNG's Sub filter undone for 1 or 2 bytes per pixel, eight bytes at a time: a running sum of every bpp-th byte.
void unfilter_sub(const unsigned char* in, unsigned char* out, std::size_t stride, std::size_t bpp) {
  std::uint64_t carry = 0;  // the last pixel so far, in every lane
  std::size_t i = 0;
  for (; i + 8 <= stride; i += 8) {
    std::uint64_t bytes = 0;
    std::memcpy(&bytes, in + i, 8);
    bytes = add_bytes(bytes, bytes << (8 * bpp));
    bytes = add_bytes(bytes, bytes << (16 * bpp));
    if (bpp == 1) bytes = add_bytes(bytes, bytes << 32);
    bytes = add_bytes(bytes, carry);
    std::memcpy(out + i, &bytes, 8);
    carry = bpp == 1 ? (bytes >> 56) * 0x0101010101010101u : (bytes >> 48) * 0x0001000100010001u;
  }
  for (; i < stride; ++i) out[i] = static_cast<unsigned char>(in[i] + (i >= bpp ? out[i - bpp] : 0));
}

// One row's filter (PNG specification, section 9) undone into `out`, given the previous row `above`; false for a
// filter type that does not exist.
bool unfilter_row(int filter, const unsigned char* in, const unsigned char* above, unsigned char* out,
                  std::size_t stride, std::size_t bpp) {
  const auto left = [&](std::size_t i) { return i >= bpp ? int{out[i - bpp]} : 0; };
  switch (filter) {
    case 0:
      std::memcpy(out, in, stride);
      return true;
    case 1:
      unfilter_sub(in, out, stride, bpp);
      return true;
    case 2:
      for (std::size_t i = 0; i < stride; ++i) out[i] = static_cast<unsigned char>(in[i] + above[i]);
      return true;
    case 3:
      for (std::size_t i = 0; i < stride; ++i) out[i] = static_cast<unsigned char>(in[i] + ((left(i) + above[i]) >> 1));
      return true;
    case 4:
      for (std::size_t i = 0; i < stride; ++i) {
        const int a = left(i), b = above[i], c = i >= bpp ? int{above[i - bpp]} : 0;
        const int pa = std::abs(b - c), pb = std::abs(a - c), pc = std::abs(a + b - 2 * c);
        out[i] = static_cast<unsigned char>(in[i] + (pa <= pb && pa <= pc ? a : pb <= pc ? b : c));
      }
      return true;
    default:
      return false;
  }
}

void swap_bytes(cv::Mat& image, int row) {
  auto* samples = image.ptr<std::uint16_t>(row);
  for (int x = 0; x < image.cols; ++x) samples[x] = static_cast<std::uint16_t>(__builtin_bswap16(samples[x]));
}

}  // namespace

std::optional<cv::Mat> decode_gray_png(const std::filesystem::path& file) {
  const std::string text = read_input_file(file, kMaxGrayPngBytes, "a grey PNG");
  const auto* bytes = reinterpret_cast<const unsigned char*>(text.data());
  const std::size_t size = text.size();
  constexpr unsigned char kSignature[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
  if (size < 8 || std::memcmp(bytes, kSignature, 8) != 0) return std::nullopt;

  std::uint32_t width = 0, height = 0;
  int bit_depth = 0;
  std::vector<unsigned char> compressed;
  bool header = false, data_ended = false, end = false;
  for (std::size_t at = 8; !end;) {
    if (size - at < 12) return std::nullopt;
    const std::uint32_t length = big_endian_32(&bytes[at]);
    if (length > size - at - 12) return std::nullopt;
    const unsigned char* type = &bytes[at + 4];
    const unsigned char* data = type + 4;
    const bool critical = (type[0] & 0x20) == 0;
    if (critical && libdeflate_crc32(0, type, length + 4) != big_endian_32(data + length)) return std::nullopt;
    if (!header) {
      // IHDR: width, height, bit depth, colour type 0 (grey), compression 0, filter method 0, no interlace.
      if (!is_type(type, "IHDR") || length != 13) return std::nullopt;
      width = big_endian_32(data);
      height = big_endian_32(data + 4);
      bit_depth = data[8];
      if (width == 0 || height == 0 || width > 0x7fffffffu || height > 0x7fffffffu) return std::nullopt;
      if ((bit_depth != 8 && bit_depth != 16) || data[9] != 0 || data[10] != 0 || data[11] != 0 || data[12] != 0) {
        return std::nullopt;
      }
      header = true;
    } else if (is_type(type, "IDAT")) {
      if (data_ended) return std::nullopt;  // image data must be consecutive chunks
      compressed.insert(compressed.end(), data, data + length);
    } else if (is_type(type, "IEND")) {
      end = true;
    } else if (critical || is_type(type, "tRNS") || is_type(type, "eXIf")) {
      return std::nullopt;  // a palette or an unknown critical chunk; transparency; an orientation cv::imread applies
    } else {
      data_ended = !compressed.empty();
    }
    at += 12 + std::size_t{length};
  }
  if (compressed.empty()) return std::nullopt;

  const std::size_t bpp = static_cast<std::size_t>(bit_depth) / 8;
  const std::size_t stride = width * bpp;
  const std::size_t filtered_bytes = height * (stride + 1);
  constexpr std::size_t kDeflateMaxRatio = 1032;  // no stream inflates further: refused before allocating for it
  if (filtered_bytes / kDeflateMaxRatio > compressed.size()) return std::nullopt;
  const std::unique_ptr<libdeflate_decompressor, decltype(&libdeflate_free_decompressor)> inflater(
      libdeflate_alloc_decompressor(), &libdeflate_free_decompressor);
  std::vector<unsigned char> filtered(filtered_bytes);
  std::size_t inflated = 0;
  if (inflater == nullptr ||
      libdeflate_zlib_decompress(inflater.get(), compressed.data(), compressed.size(), filtered.data(), filtered_bytes,
                                 &inflated) != LIBDEFLATE_SUCCESS ||
      inflated != filtered_bytes) {
    return std::nullopt;
  }
  const std::vector<unsigned char> zeros(stride, 0);  // the row above the first
  cv::Mat image(static_cast<int>(height), static_cast<int>(width), bit_depth == 16 ? CV_16UC1 : CV_8UC1);
  for (int y = 0; y < image.rows; ++y) {
    const unsigned char* row = &filtered[static_cast<std::size_t>(y) * (stride + 1)];
    const unsigned char* above = y > 0 ? image.ptr<unsigned char>(y - 1) : zeros.data();
    if (!unfilter_row(row[0], row + 1, above, image.ptr<unsigned char>(y), stride, bpp)) return std::nullopt;
    if (bpp == 2 && y > 0) swap_bytes(image, y - 1);  // big-endian samples, once the next row has used them
  }
  if (bpp == 2) swap_bytes(image, image.rows - 1);
  return image;
}

}  // namespace rfrecon
