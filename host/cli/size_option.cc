// Parsing of "WxH" size values on the command line.
#include "host/cli/size_option.h"

#include <charconv>

#include "host/core/errors.h"
#include "host/core/limits.h"

namespace rfrecon::cli {

namespace {
// Parses [first, last) as a whole integer of at most 6 characters; false on anything else.
bool parse_dimension(const char* first, const char* last, int& value) {
  if (last - first < 1 || last - first > 6) return false;
  const auto [end, error] = std::from_chars(first, last, value);
  return error == std::errc() && end == last;
}
}  // namespace

cv::Size parse_size(const std::string& text, const std::string& option) {
  const auto separator = text.find_first_of("xX");
  int width = 0;
  int height = 0;
  if (separator != std::string::npos && parse_dimension(text.data(), text.data() + separator, width) &&
      parse_dimension(text.data() + separator + 1, text.data() + text.size(), height) && width > 0 && height > 0) {
    if (width > kMaxImageSide || height > kMaxImageSide) {
      throw UsageError(option + " " + text + ": at most " + std::to_string(kMaxImageSide) + " px a side");
    }
    return {width, height};
  }
  throw UsageError(option + ": expected WIDTHxHEIGHT with positive integers (e.g. 1024x768), got '" + text + "'");
}

}  // namespace rfrecon::cli
