// Rendering the protocol's patterns into a staging directory with their manifest.
#include "host/capture/pattern_files.h"

#include <cstdio>

#include "host/capture/pattern_family.h"
#include "host/core/atomic_file.h"
#include "host/core/image_file.h"

namespace rfrecon::capture {

std::string pattern_file_name(std::size_t index, const Pattern& pattern, const std::string& family,
                              const std::string& extension) {
  char number[24];
  std::snprintf(number, sizeof number, "%03zu_", index);
  return number + pattern_family(family).file_stem(pattern) + extension;
}

std::vector<Frame> protocol_frames(const ProtocolOptions& protocol, const std::string& extension) {
  const auto sequence = make_protocol(protocol);
  std::vector<Frame> frames;
  frames.reserve(sequence.size());
  for (std::size_t i = 0; i < sequence.size(); ++i)
    frames.push_back({sequence[i], pattern_file_name(i, sequence[i], protocol.family, extension)});
  return frames;
}

CaptureManifest write_pattern_directory(const std::filesystem::path& out_dir, const ProtocolOptions& protocol,
                                        bool force) {
  StagingDirectory staging(out_dir, force);
  CaptureManifest manifest;
  manifest.family = protocol.family;
  manifest.projector_size = protocol.projector_size;
  manifest.dot_spacing = protocol.dot_spacing;
  manifest.parameters = protocol.parameters;
  manifest.frames = protocol_frames(protocol);
  for (const auto& frame : manifest.frames)
    write_image(staging.path() / frame.file, render_pattern(frame.pattern, protocol));
  write_manifest(manifest, staging.path());
  staging.commit();
  return manifest;
}

}  // namespace rfrecon::capture
