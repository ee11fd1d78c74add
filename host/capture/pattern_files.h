// `rfrecon patterns` as a library call: the projector images of the capture protocol and their manifest, on disk.
#pragma once

#include <cstddef>
#include <filesystem>
#include <string>
#include <vector>

#include "host/capture/manifest.h"

namespace rfrecon::capture {

// The file of frame `index` of a capture of `family`: "007_gray_col_b02_inv.png", "040_dot_03_05.png",
// "000_white.png" (the sequence number keeps name order equal to projection order). `extension` includes the dot.
std::string pattern_file_name(std::size_t index, const Pattern& pattern, const std::string& family = kDefaultFamily,
                              const std::string& extension = ".png");

// The frames of make_protocol(protocol), each with its pattern_file_name: a manifest's frame list.
std::vector<Frame> protocol_frames(const ProtocolOptions& protocol, const std::string& extension = ".png");

// Writes one PNG per pattern of make_protocol(protocol) and the manifest into `out_dir`, which appears whole or not
// at all. An existing non-empty out_dir is an InputError unless `force`, and is then replaced. Returns the manifest.
CaptureManifest write_pattern_directory(const std::filesystem::path& out_dir, const ProtocolOptions& protocol,
                                        bool force);

}  // namespace rfrecon::capture
