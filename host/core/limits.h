// The stated maxima for sizes read from files and options (docs/formats.md#limits), checked before any allocation.
#pragma once

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <string>

#include <opencv2/core.hpp>

namespace rfrecon {

inline constexpr int kMaxImageSide = 16384;                 // px: camera or projector width or height
inline constexpr std::int64_t kMaxImagePixels = 1LL << 26;  // 67 M pixels, e.g. 8192 x 8192

// Throws InputError "WHAT: size WxH is over the limit ..." unless both sides are in [0, kMaxImageSide] and the area
// is at most kMaxImagePixels.
void check_image_size(cv::Size size, const std::string& what);

// Throws InputError naming `what` when `bytes` exceeds the machine's physical memory: a request that would only
// end in bad_alloc or swapping is refused before it starts.
void check_memory(double bytes, const std::string& what);

// Text files are read whole, so each reader caps its file's size first (docs/formats.md#limits). Nesting in JSON and
// YAML is capped too: parsers and the code walking their trees recurse once per level.
inline constexpr std::size_t kMaxJsonBytes = std::size_t{16} << 20;  // 16 MiB: a corners.json is under 1 MB
inline constexpr int kMaxNestingDepth = 64;                          // arrays and objects inside one another

// A grey PNG is read whole to be decoded (host/core/gray_png.h): twice the largest 16-bit image stored uncompressed.
inline constexpr std::size_t kMaxGrayPngBytes = std::size_t{4} * kMaxImagePixels;

// The bytes of `file`, read only once check_input_file passed (no open that could block) and refused with an
// InputError "FILE: N bytes, over the limit of M for WHAT (docs/formats.md#limits)" when larger than `max_bytes`.
std::string read_input_file(const std::filesystem::path& file, std::size_t max_bytes, const std::string& what);

}  // namespace rfrecon
