// Parsing of "WxH" size values on the command line.
#include "host/cli/size_option.h"

#include <regex>

#include "host/common/errors.h"

namespace rfrecon::cli {

cv::Size parse_size(const std::string& text, const std::string& option) {
  static const std::regex pattern(R"(^([0-9]{1,6})[xX]([0-9]{1,6})$)");
  std::smatch match;
  if (std::regex_match(text, match, pattern)) {
    const cv::Size size(std::stoi(match[1].str()), std::stoi(match[2].str()));
    if (size.width > 0 && size.height > 0) return size;
  }
  throw InputError(option + ": expected WIDTHxHEIGHT with positive integers (e.g. 1024x768), got '" + text + "'");
}

}  // namespace rfrecon::cli
