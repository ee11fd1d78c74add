// Parsing of "WxH" size values on the command line (e.g. --projector 1024x768).
#pragma once

#include <string>

#include <opencv2/core.hpp>

namespace rfrecon::cli {

// "1024x768" -> {1024, 768}; throws UsageError naming `option` unless both are positive integers of at most
// kMaxImageSide (host/core/limits.h).
cv::Size parse_size(const std::string& text, const std::string& option);

}  // namespace rfrecon::cli
