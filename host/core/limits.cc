// Size and memory limits with messages that name the offending file or option.
#include "host/core/limits.h"

#include <unistd.h>

#include "host/core/errors.h"

namespace rfrecon {

void check_image_size(cv::Size size, const std::string& what) {
  if (size.width < 0 || size.height < 0 || size.width > kMaxImageSide || size.height > kMaxImageSide ||
      static_cast<std::int64_t>(size.width) * size.height > kMaxImagePixels) {
    throw InputError(what + ": size " + std::to_string(size.width) + "x" + std::to_string(size.height) +
                     " is over the limit (at most " + std::to_string(kMaxImageSide) + " px a side and " +
                     std::to_string(kMaxImagePixels) + " pixels)");
  }
}

void check_memory(double bytes, const std::string& what) {
  const double physical = static_cast<double>(::sysconf(_SC_PHYS_PAGES)) * static_cast<double>(::sysconf(_SC_PAGESIZE));
  if (physical > 0 && bytes > physical) {
    throw InputError(what + " needs " + std::to_string(static_cast<long long>(bytes / (1 << 20))) +
                     " MiB, more than this machine's " + std::to_string(static_cast<long long>(physical / (1 << 20))) +
                     " MiB of memory");
  }
}

}  // namespace rfrecon
