// libFuzzer target: an image file (read_image_header, then decode_image as frames and truth maps are read).
// InputError is the documented rejection; any other exception, crash or sanitizer report is a finding.
#include <opencv2/imgcodecs.hpp>

#include "host/core/errors.h"
#include "host/core/image_file.h"
#include "host/core/image_header.h"
#include "tests/fuzz/fuzz_files.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const rfrecon::fuzz::ScratchDir scratch;
  const auto file = scratch.path() / "image";
  rfrecon::fuzz::write_file(file, data, size);
  try {
    (void)rfrecon::read_image_header(file);
    (void)rfrecon::decode_image(file, cv::IMREAD_UNCHANGED);
    (void)rfrecon::decode_image(file, cv::IMREAD_GRAYSCALE | cv::IMREAD_ANYDEPTH);
  } catch (const rfrecon::InputError&) {
  }
  return 0;
}
