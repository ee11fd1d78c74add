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

std::vector<Frame> protocol_frames(const ProtocolOptions& protocol, const std::string& extension) {
  const auto sequence = make_protocol(protocol);
  std::vector<Frame> frames;
  frames.reserve(sequence.size());
  for (std::size_t i = 0; i < sequence.size(); ++i)
    frames.push_back({sequence[i], pattern_file_name(i, sequence[i], extension)});
  return frames;
}

CaptureManifest write_pattern_directory(const std::filesystem::path& out_dir, const ProtocolOptions& protocol,
                                        bool force) {
  StagingDirectory staging(out_dir, force);
  CaptureManifest manifest;
  manifest.projector_size = protocol.projector_size;
  manifest.dot_spacing = protocol.dot_spacing;
  manifest.frames = protocol_frames(protocol);
  for (const auto& frame : manifest.frames) {
    write_image(staging.path() / frame.file,
                render_pattern(frame.pattern, protocol.projector_size, protocol.dot_spacing));
  }
  write_manifest(manifest, staging.path());
  staging.commit();
  return manifest;
}

}  // namespace rfrecon::capture
