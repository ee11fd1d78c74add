// The s x s dot grid that samples the light transport itself, as any pattern family appends it after its own patterns:
// frames lighting projector pixels with x % s == ox and y % s == oy, ox fastest; their images, file names, manifest
// entries and completeness check.
#pragma once

#include <string>
#include <vector>

#include <nlohmann/json_fwd.hpp>
#include <opencv2/core.hpp>

#include "host/capture/manifest.h"

namespace rfrecon::capture {

inline constexpr int kMaxDotSpacing = 64;  // s x s = 4096 dot frames at most

// Throws InputError unless the spacing is 0 (no dot grid) or 2 to kMaxDotSpacing.
void check_dot_spacing(int dot_spacing);

// Appends the grid's s x s frames (none for spacing 0).
void append_dot_grid(std::vector<Pattern>& sequence, int dot_spacing);

// Lights the dot frame's pixels (255) in `image`, CV_8UC1 of the projector.
void render_dot(const Pattern& dot, int dot_spacing, cv::Mat& image);

// "dot_03_05": offsets x, y.
std::string dot_file_stem(const Pattern& dot);

// The entry's "dot_offset": [x, y], and back (InputError starting with `where`).
void write_dot_entry(const Pattern& dot, nlohmann::json& entry);
void read_dot_entry(const nlohmann::json& entry, const std::string& where, Pattern& dot);

// Throws InputError starting with `where` unless the manifest's dot frames are its whole grid, each offset once.
void validate_dot_grid(const CaptureManifest& manifest, const std::string& where);

}  // namespace rfrecon::capture
