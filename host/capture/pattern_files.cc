// Rendering the protocol's patterns into a staging directory with their manifest.
#include "host/capture/pattern_files.h"

#include <cstdio>

#include "host/core/atomic_file.h"
#include "host/core/image_file.h"

namespace rfrecon::capture {

std::string pattern_file_name(std::size_t index, const Pattern& pattern, const std::string& extension) {
  char name[96];
  if (pattern.kind == PatternKind::kGrayColumn || pattern.kind == PatternKind::kGrayRow) {
    std::snprintf(name, sizeof name, "%03zu_%s_b%02d%s", index, to_string(pattern.kind), pattern.bit,
                  pattern.inverse ? "_inv" : "");
  } else if (pattern.kind == PatternKind::kDot) {
    std::snprintf(name, sizeof name, "%03zu_dot_%02d_%02d", index, pattern.dot_offset_x, pattern.dot_offset_y);
  } else {
    std::snprintf(name, sizeof name, "%03zu_%s", index, to_string(pattern.kind));
  }
  return name + extension;
}

CaptureManifest write_pattern_directory(const std::filesystem::path& out_dir, const ProtocolOptions& protocol,
                                        bool force) {
  const auto sequence = make_protocol(protocol);
  StagingDirectory staging(out_dir, force);
  CaptureManifest manifest;
  manifest.projector_size = protocol.projector_size;
  manifest.dot_spacing = protocol.dot_spacing;
  for (std::size_t i = 0; i < sequence.size(); ++i) {
    const std::string file = pattern_file_name(i, sequence[i]);
    write_image(staging.path() / file, render_pattern(sequence[i], protocol.projector_size, protocol.dot_spacing));
    manifest.frames.push_back({sequence[i], file});
  }
  write_manifest(manifest, staging.path());
  staging.commit();
  return manifest;
}

}  // namespace rfrecon::capture
