// PNG IHDR, TIFF first directory, JPEG frame header, BMP info header and PNM header fields, read with bounds checks.
#include "host/core/image_header.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <fstream>
#include <optional>
#include <string_view>
#include <system_error>
#include <vector>

#include "host/core/errors.h"
#include "host/core/input_file.h"

namespace rfrecon {

namespace fs = std::filesystem;

namespace {

constexpr double kDeflateRatio = 1032;  // zlib's largest: 258 bytes from about 2 bits
constexpr double kLzwRatio = 4096;      // TIFF LZW: at most about 3,840 bytes from one 12-bit code
constexpr double kPackBitsRatio = 64;   // 128 bytes from 2
constexpr int kMaxTiffEntries = 4096;   // libtiff's own limit on a directory
constexpr int kMaxPnmDigits = 10;       // a PNM header number: up to 9,999,999,999
constexpr std::size_t kWindowBytes = 4096;

// Random access to a file's bytes through a small window; a read past the end is a truncated header.
class FileBytes {
 public:
  explicit FileBytes(const fs::path& file) : file_(file), in_(file, std::ios::binary) {
    std::error_code error;
    size_ = fs::file_size(file, error);
    if (!in_ || error) fail("cannot be opened (permission?)");
  }

  [[noreturn]] void fail(const std::string& what) const { throw InputError(file_.string() + ": " + what); }

  // `count` bytes at `offset`; at most the bytes the file has when `up_to_end`.
  std::string text(std::uint64_t offset, std::size_t count, bool up_to_end = false) {
    std::string bytes;
    const std::uint64_t end = up_to_end ? std::min<std::uint64_t>(offset + count, size_) : offset + count;
    for (std::uint64_t i = offset; i < end; ++i) bytes += static_cast<char>(byte(i));
    return bytes;
  }

  std::uint8_t byte(std::uint64_t offset) {
    if (offset >= size_) fail(format + " header is truncated (the file ends at byte " + std::to_string(size_) + ")");
    if (offset < window_start_ || offset - window_start_ >= window_.size()) load(offset);
    return window_[offset - window_start_];
  }

  // `count` (1 to 8) bytes at `offset` as an unsigned number.
  std::uint64_t number(std::uint64_t offset, int count, bool little_endian) {
    std::uint64_t value = 0;
    for (int i = 0; i < count; ++i) {
      const std::uint64_t at = offset + static_cast<std::uint64_t>(little_endian ? count - 1 - i : i);
      if (at < offset) fail(format + " header points past any file size");
      value = (value << 8) | byte(at);
    }
    return value;
  }

  std::string format;  // for messages, set once the magic number is known

 private:
  void load(std::uint64_t offset) {
    window_.resize(static_cast<std::size_t>(std::min<std::uint64_t>(kWindowBytes, size_ - offset)));
    in_.clear();
    in_.seekg(static_cast<std::streamoff>(offset));
    if (!in_.read(window_.data(), static_cast<std::streamsize>(window_.size()))) {
      window_.clear();
      fail("cannot be read at byte " + std::to_string(offset) + " (changed while reading?)");
    }
    window_start_ = offset;
  }

  fs::path file_;
  std::ifstream in_;
  std::uint64_t size_ = 0;
  std::vector<char> window_;
  std::uint64_t window_start_ = 0;
};

// Bytes as a whole number, rounded up and held below 2^63 (declared sizes can exceed any file).
std::uint64_t whole_bytes(double bytes) { return static_cast<std::uint64_t>(std::min(std::ceil(bytes), 9.0e18)); }

// A declared side as a signed number (sides beyond 2^62 are refused as over the limit all the same).
std::int64_t side(std::uint64_t value) { return static_cast<std::int64_t>(std::min<std::uint64_t>(value, 1ULL << 62)); }

int bytes_per_sample(std::uint64_t bits) { return bits <= 8 ? 1 : bits <= 16 ? 2 : bits <= 32 ? 4 : 8; }

// Rows of `row_bits` bits, each padded to `row_align_bytes`.
double rows_bytes(const ImageHeader& header, double row_bits, double row_align_bytes = 1) {
  return std::ceil(row_bits / 8 / row_align_bytes) * row_align_bytes * static_cast<double>(header.height);
}

ImageHeader png_header(FileBytes& bytes) {
  if (bytes.text(12, 4) != "IHDR") bytes.fail("a PNG whose first chunk is not IHDR");
  ImageHeader header{"PNG", side(bytes.number(16, 4, false)), side(bytes.number(20, 4, false))};
  const int bit_depth = bytes.byte(24);
  const int color_type = bytes.byte(25);
  constexpr std::array<int, 7> kStoredSamples{1, 0, 3, 1, 2, 0, 4};  // by color type; 0: no such type
  if (color_type >= static_cast<int>(kStoredSamples.size()) || kStoredSamples[color_type] == 0) {
    bytes.fail("PNG color type " + std::to_string(color_type) + " does not exist");
  }
  header.channels = color_type == 0 ? 1 : color_type == 2 ? 3 : 4;  // a palette may decode with alpha
  header.bytes_per_sample = bytes_per_sample(bit_depth);
  // Every row starts with a filter byte; the rows are one zlib stream.
  const double row_bits = static_cast<double>(header.width) * kStoredSamples[color_type] * bit_depth + 8;
  header.min_file_bytes = whole_bytes(rows_bytes(header, row_bits) / kDeflateRatio);
  return header;
}

// TIFF and BigTIFF: the first directory's ImageWidth, ImageLength, BitsPerSample, Compression, SamplesPerPixel.
class TiffDirectory {
 public:
  TiffDirectory(FileBytes& bytes, bool little, bool big_tiff)
      : bytes_(bytes), little_(little), offset_bytes_(big_tiff ? 8 : 4) {
    if (big_tiff && (bytes.number(4, 2, little) != 8 || bytes.number(6, 2, little) != 0)) {
      bytes.fail("BigTIFF header without 8-byte offsets");
    }
    const std::uint64_t directory = bytes.number(big_tiff ? 8 : 4, offset_bytes_, little);
    const std::uint64_t count = bytes.number(directory, offset_bytes_ == 8 ? 8 : 2, little);
    if (count > kMaxTiffEntries) {
      bytes.fail("TIFF directory of " + std::to_string(count) + " entries (at most " + std::to_string(kMaxTiffEntries) +
                 ")");
    }
    first_entry_ = directory + (offset_bytes_ == 8 ? 8 : 2);
    count_ = static_cast<int>(count);
  }

  // The first value of `tag` (SHORT, LONG or LONG8); nullopt when the directory lacks it.
  std::optional<std::uint64_t> value(std::uint16_t tag) {
    const std::uint64_t entry_bytes = offset_bytes_ == 8 ? 20 : 12;
    for (int i = 0; i < count_; ++i) {
      const std::uint64_t entry = first_entry_ + entry_bytes * static_cast<std::uint64_t>(i);
      if (bytes_.number(entry, 2, little_) != tag) continue;
      const std::uint64_t type = bytes_.number(entry + 2, 2, little_);
      const int size = type == 3 ? 2 : type == 4 ? 4 : type == 16 ? 8 : 0;
      if (size == 0) bytes_.fail("TIFF tag " + std::to_string(tag) + " has type " + std::to_string(type));
      const std::uint64_t count = bytes_.number(entry + 4, offset_bytes_, little_);
      const std::uint64_t field = entry + 4 + static_cast<std::uint64_t>(offset_bytes_);
      const bool inline_values = count <= static_cast<std::uint64_t>(offset_bytes_ / size);
      return bytes_.number(inline_values ? field : bytes_.number(field, offset_bytes_, little_), size, little_);
    }
    return std::nullopt;
  }

 private:
  FileBytes& bytes_;
  bool little_;
  int offset_bytes_;
  std::uint64_t first_entry_ = 0;
  int count_ = 0;
};

// The largest ratio of raw to stored bytes of a TIFF compression; 0 for one without a bound.
double tiff_ratio(std::uint64_t compression) {
  switch (compression) {
    case 1:
      return 1;
    case 5:
      return kLzwRatio;
    case 8:
    case 32946:
      return kDeflateRatio;
    case 32773:
      return kPackBitsRatio;
    default:
      return 0;
  }
}

ImageHeader tiff_header(FileBytes& bytes, bool little, bool big_tiff) {
  TiffDirectory directory(bytes, little, big_tiff);
  const auto width = directory.value(256);
  const auto height = directory.value(257);
  if (!width || !height) bytes.fail("TIFF without ImageWidth or ImageLength");
  ImageHeader header{"TIFF", side(*width), side(*height)};
  const std::uint64_t bits = directory.value(258).value_or(1);
  const std::uint64_t samples = directory.value(277).value_or(1);
  if (samples < 1 || samples > 4) {
    bytes.fail("TIFF of " + std::to_string(samples) + " samples per pixel (rfrecon reads 1 to 4)");
  }
  if (bits < 1 || bits > 64) bytes.fail("TIFF of " + std::to_string(bits) + " bits per sample (1 to 64)");
  const bool whole_bytes_per_sample = bits == 8 || bits == 16 || bits == 32 || bits == 64;
  header.channels = whole_bytes_per_sample ? static_cast<int>(samples) : 4;  // others decode through 8-bit RGBA
  header.bytes_per_sample = whole_bytes_per_sample ? bytes_per_sample(bits) : 1;
  const double ratio = tiff_ratio(directory.value(259).value_or(1));
  const double row_bits = static_cast<double>(header.width) * static_cast<double>(samples * bits);
  if (ratio > 0) header.min_file_bytes = whole_bytes(rows_bytes(header, row_bits) / ratio);
  return header;
}

bool is_jpeg_frame_marker(int marker) {
  return marker >= 0xC0 && marker <= 0xCF && marker != 0xC4 && marker != 0xC8 && marker != 0xCC;
}

// The first frame header (SOFn) among the segments after SOI.
ImageHeader jpeg_header(FileBytes& bytes) {
  std::uint64_t offset = 2;
  for (;;) {
    if (bytes.byte(offset) != 0xFF) bytes.fail("JPEG without a marker at byte " + std::to_string(offset));
    while (bytes.byte(offset + 1) == 0xFF) ++offset;  // fill bytes
    const int marker = bytes.byte(offset + 1);
    if (marker == 0xD9 || marker == 0xDA) bytes.fail("JPEG without a frame header (SOF) before its data");
    if (marker == 0x01 || (marker >= 0xD0 && marker <= 0xD7)) {  // markers without a length
      offset += 2;
      continue;
    }
    if (is_jpeg_frame_marker(marker)) break;
    const std::uint64_t length = bytes.number(offset + 2, 2, false);
    if (length < 2) {
      bytes.fail("JPEG segment of length " + std::to_string(length) + " at byte " + std::to_string(offset));
    }
    offset += 2 + length;
  }
  const int marker = bytes.byte(offset + 1);
  ImageHeader header{"JPEG", side(bytes.number(offset + 7, 2, false)), side(bytes.number(offset + 5, 2, false))};
  header.bytes_per_sample = bytes.byte(offset + 4) > 8 ? 2 : 1;
  header.channels = std::clamp<int>(bytes.byte(offset + 9), 1, 4);
  // Baseline and extended Huffman coding spend at least 2 bits (a DC and an end-of-block code) on each 8x8 block of
  // the full-resolution component.
  if (marker == 0xC0 || marker == 0xC1) {
    const double blocks =
        std::ceil(static_cast<double>(header.width) / 8) * std::ceil(static_cast<double>(header.height) / 8);
    header.min_file_bytes = whole_bytes(blocks * 2 / 8);
  }
  return header;
}

std::int64_t signed_32(std::uint64_t value) { return static_cast<std::int32_t>(static_cast<std::uint32_t>(value)); }

ImageHeader bmp_header(FileBytes& bytes) {
  const std::uint64_t info_bytes = bytes.number(14, 4, true);
  const bool core = info_bytes == 12;  // OS/2 BITMAPCOREHEADER: 16-bit sizes
  if (!core && info_bytes < 36) bytes.fail("BMP info header of " + std::to_string(info_bytes) + " bytes");
  ImageHeader header{"BMP", core ? side(bytes.number(18, 2, true)) : signed_32(bytes.number(18, 4, true)),
                     core ? side(bytes.number(20, 2, true)) : signed_32(bytes.number(22, 4, true))};
  if (header.width < 0) bytes.fail("BMP width " + std::to_string(header.width));
  header.height = std::abs(header.height);  // negative: rows top-down
  const std::uint64_t bits = bytes.number(core ? 24 : 28, 2, true);
  const std::uint64_t compression = core ? 0 : bytes.number(30, 4, true);
  header.channels = bits == 32 ? 4 : 3;
  if (compression == 0 || compression == 3) {  // BI_RGB, BI_BITFIELDS: rows padded to 4 bytes from the data offset
    const double data = rows_bytes(header, static_cast<double>(header.width) * static_cast<double>(bits), 4);
    header.min_file_bytes = whole_bytes(static_cast<double>(bytes.number(10, 4, true)) + data);
  }
  return header;
}

bool is_pnm_space(std::uint8_t c) { return c == ' ' || c == '\t' || c == '\n' || c == '\r' || c == '\v' || c == '\f'; }

// The next decimal number of a PNM header at `offset`, after whitespace and comments; `offset` moves past it.
std::uint64_t pnm_number(FileBytes& bytes, std::uint64_t& offset) {
  for (;;) {
    const std::uint8_t c = bytes.byte(offset);
    if (c == '#') {
      while (bytes.byte(offset) != '\n' && bytes.byte(offset) != '\r') ++offset;
    } else if (is_pnm_space(c)) {
      ++offset;
    } else {
      break;
    }
  }
  std::uint64_t value = 0;
  int digits = 0;
  for (std::uint8_t c = bytes.byte(offset); c >= '0' && c <= '9'; c = bytes.byte(++offset)) {
    if (++digits > kMaxPnmDigits) {
      bytes.fail("PNM header number longer than " + std::to_string(kMaxPnmDigits) + " digits");
    }
    value = value * 10 + (c - '0');
  }
  if (digits == 0) bytes.fail("PNM header without a number at byte " + std::to_string(offset));
  return value;
}

// P1 to P6: width, height and (but for bitmaps) the largest sample value; one whitespace byte, then the samples.
ImageHeader pnm_header(FileBytes& bytes) {
  const int kind = bytes.byte(1) - '0';
  const bool bitmap = kind == 1 || kind == 4;
  const bool ascii = kind <= 3;
  std::uint64_t offset = 2;
  ImageHeader header{"PNM"};
  header.width = side(pnm_number(bytes, offset));
  header.height = side(pnm_number(bytes, offset));
  const std::uint64_t max_value = bitmap ? 1 : pnm_number(bytes, offset);
  if (max_value < 1 || max_value > 65535) {
    bytes.fail("PNM largest value " + std::to_string(max_value) + " (1 to 65535)");
  }
  header.channels = kind == 3 || kind == 6 ? 3 : 1;
  header.bytes_per_sample = max_value > 255 ? 2 : 1;
  const double samples = static_cast<double>(header.width) * static_cast<double>(header.height) * header.channels;
  const double data = ascii       ? samples  // at least one character each
                      : kind == 4 ? rows_bytes(header, static_cast<double>(header.width))
                                  : samples * header.bytes_per_sample;
  header.min_file_bytes = whole_bytes(static_cast<double>(offset + 1) + data);
  return header;
}

bool starts_with(std::string_view text, std::string_view prefix) { return text.substr(0, prefix.size()) == prefix; }

}  // namespace

ImageHeader read_image_header(const fs::path& file) {
  check_input_file(file);
  FileBytes bytes(file);
  const std::string magic = bytes.text(0, 8, true);
  const auto parse = [&](const char* format, auto&& parser) {
    bytes.format = format;
    return parser();
  };
  using namespace std::string_view_literals;
  if (starts_with(magic, "\x89PNG\r\n\x1a\n"sv)) return parse("PNG", [&] { return png_header(bytes); });
  if (starts_with(magic, "II*\0"sv)) return parse("TIFF", [&] { return tiff_header(bytes, true, false); });
  if (starts_with(magic, "MM\0*"sv)) return parse("TIFF", [&] { return tiff_header(bytes, false, false); });
  if (starts_with(magic, "II+\0"sv)) return parse("TIFF", [&] { return tiff_header(bytes, true, true); });
  if (starts_with(magic, "MM\0+"sv)) return parse("TIFF", [&] { return tiff_header(bytes, false, true); });
  if (starts_with(magic, "\xFF\xD8\xFF"sv)) return parse("JPEG", [&] { return jpeg_header(bytes); });
  if (starts_with(magic, "BM"sv)) return parse("BMP", [&] { return bmp_header(bytes); });
  if (magic.size() >= 3 && magic[0] == 'P' && magic[1] >= '1' && magic[1] <= '6' && is_pnm_space(magic[2])) {
    return parse("PNM", [&] { return pnm_header(bytes); });
  }
  bytes.fail("not an image rfrecon reads (PNG, TIFF, JPEG, BMP, or PNM: PBM, PGM, PPM)");
}

}  // namespace rfrecon
