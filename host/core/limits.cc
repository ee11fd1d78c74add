// Size and memory limits with messages that name the offending file or option.
#include "host/core/limits.h"

#include <array>
#include <fstream>

#include <unistd.h>

#include "host/core/errors.h"
#include "host/core/input_file.h"

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

std::string read_input_file(const std::filesystem::path& file, std::size_t max_bytes, const std::string& what) {
  check_input_file(file);
  const auto refuse = [&](const std::string& size) {
    throw InputError(file.string() + ": " + size + " bytes, over the limit of " + std::to_string(max_bytes) + " for " +
                     what + " (docs/formats.md#limits)");
  };
  std::error_code ec;
  const std::uintmax_t size = std::filesystem::file_size(file, ec);
  if (!ec && size > max_bytes) refuse(std::to_string(size));
  std::ifstream in(file, std::ios::binary);
  if (!in) throw InputError("cannot read " + file.string());
  std::string bytes;
  bytes.reserve(ec ? 0 : static_cast<std::size_t>(size));
  std::array<char, 1 << 16> chunk{};
  while (in.read(chunk.data(), chunk.size()) || in.gcount() > 0) {  // the file may have grown since its stat
    bytes.append(chunk.data(), static_cast<std::size_t>(in.gcount()));
    if (bytes.size() > max_bytes) refuse("more than " + std::to_string(max_bytes));
  }
  return bytes;
}

}  // namespace rfrecon
