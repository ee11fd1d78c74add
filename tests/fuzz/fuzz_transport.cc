// libFuzzer target: a T.h5 (transport::read_transport, HDF5). InputError is the documented rejection; any other
// exception (H5::Exception included), crash or sanitizer report is a finding.
#include "host/core/errors.h"
#include "host/transport/transport_file.h"
#include "tests/fuzz/fuzz_files.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const rfrecon::fuzz::ScratchDir scratch;
  const auto file = scratch.path() / "T.h5";
  rfrecon::fuzz::write_file(file, data, size);
  try {
    (void)rfrecon::transport::read_transport(file);
  } catch (const rfrecon::InputError&) {
  }
  return 0;
}
