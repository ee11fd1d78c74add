// libFuzzer target: a scene JSON file (sim::load_scene_file). InputError is the documented rejection; any other
// exception, crash or sanitizer report is a finding.
#include "host/core/errors.h"
#include "sim/scene.h"
#include "tests/fuzz/fuzz_files.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const rfrecon::fuzz::ScratchDir scratch;
  const auto file = scratch.path() / "scene.json";
  rfrecon::fuzz::write_file(file, data, size);
  try {
    (void)rfrecon::sim::load_scene_file(file);
  } catch (const rfrecon::InputError&) {
  }
  return 0;
}
