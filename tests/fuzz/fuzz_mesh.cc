// libFuzzer target: a mesh file (sim::load_mesh: the checks of sim/mesh_file.h, then assimp). An input starting with
// "ply" is written as mesh.ply, anything else as mesh.obj. InputError is the documented
// rejection; any other exception, crash or sanitizer report, or an allocation over -rss_limit_mb, is a finding.
#include <cstring>
#include <string>

#include "host/core/errors.h"
#include "sim/objects.h"
#include "tests/fuzz/fuzz_files.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const rfrecon::fuzz::ScratchDir scratch;
  const auto starts_with = [&](const char* prefix) {
    return size >= std::strlen(prefix) && std::memcmp(data, prefix, std::strlen(prefix)) == 0;
  };
  const std::string extension = starts_with("ply") ? ".ply" : ".obj";
  const auto file = scratch.path() / ("mesh" + extension);
  rfrecon::fuzz::write_file(file, data, size);
  try {
    (void)rfrecon::sim::load_mesh(file.string(), 1.0, "objects[0].file");
  } catch (const rfrecon::InputError&) {
  }
  return 0;
}
