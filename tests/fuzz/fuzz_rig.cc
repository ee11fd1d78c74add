// libFuzzer target: a rig.yaml (calib::read_rig, OpenCV FileStorage YAML). InputError is the documented rejection;
// any other exception (cv::Exception included), crash or sanitizer report is a finding.
#include "calib/rig.h"
#include "host/core/errors.h"
#include "tests/fuzz/fuzz_files.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const rfrecon::fuzz::ScratchDir scratch;
  const auto file = scratch.path() / "rig.yaml";
  rfrecon::fuzz::write_file(file, data, size);
  try {
    (void)rfrecon::calib::read_rig(file);
  } catch (const rfrecon::InputError&) {
  }
  return 0;
}
