// The stated maxima for sizes read from files and options (docs/formats.md#limits), checked before any allocation.
#pragma once

#include <cstdint>
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

}  // namespace rfrecon
