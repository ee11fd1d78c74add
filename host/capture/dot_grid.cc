// The dot grid's frames, shared by the pattern families.
#include "host/capture/dot_grid.h"

#include <cstdio>
#include <set>
#include <utility>

#include <nlohmann/json.hpp>

#include "host/capture/pattern_family.h"
#include "host/core/errors.h"
#include "host/core/message_text.h"

namespace rfrecon::capture {

namespace {
bool dot_spacing_allowed(int dot_spacing) {
  return dot_spacing == 0 || (dot_spacing >= 2 && dot_spacing <= kMaxDotSpacing);
}
}  // namespace

void check_dot_spacing(int dot_spacing) {
  if (dot_spacing_allowed(dot_spacing)) return;
  throw InputError("dot spacing must be 0 (no dot grid) or 2 to " + std::to_string(kMaxDotSpacing) + ", got " +
                   std::to_string(dot_spacing));
}

void append_dot_grid(std::vector<Pattern>& sequence, int dot_spacing) {
  for (int oy = 0; oy < dot_spacing; ++oy) {
    for (int ox = 0; ox < dot_spacing; ++ox) {
      Pattern dot;
      dot.kind = pattern_kind::kDot;
      dot.dot_offset_x = ox;
      dot.dot_offset_y = oy;
      sequence.push_back(dot);
    }
  }
}

void render_dot(const Pattern& dot, int dot_spacing, cv::Mat& image) {
  for (int y = dot.dot_offset_y; y < image.rows; y += dot_spacing) {
    for (int x = dot.dot_offset_x; x < image.cols; x += dot_spacing) image.at<unsigned char>(y, x) = 255;
  }
}

std::string dot_file_stem(const Pattern& dot) {
  char stem[32];
  std::snprintf(stem, sizeof stem, "dot_%02d_%02d", dot.dot_offset_x, dot.dot_offset_y);
  return stem;
}

void write_dot_entry(const Pattern& dot, nlohmann::json& entry) {
  entry["dot_offset"] = nlohmann::json::array({dot.dot_offset_x, dot.dot_offset_y});
}

void read_dot_entry(const nlohmann::json& entry, const std::string& where, Pattern& dot) {
  const auto offset = entry_ints(entry, "dot_offset", where);
  if (offset.size() != 2) throw InputError(where + ": dot_offset must be [x, y]");
  dot.dot_offset_x = offset[0];
  dot.dot_offset_y = offset[1];
}

void validate_dot_grid(const CaptureManifest& manifest, const std::string& where) {
  const auto fail = [&](const std::string& what) { throw InputError(where + ": " + what); };
  if (!dot_spacing_allowed(manifest.dot_spacing))
    fail("dot_spacing must be 0 or 2 to " + std::to_string(kMaxDotSpacing));
  const int s = manifest.dot_spacing;
  std::set<std::pair<int, int>> seen;
  for (std::size_t i = 0; i < manifest.frames.size(); ++i) {
    const Pattern& pattern = manifest.frames[i].pattern;
    if (pattern.kind != pattern_kind::kDot) continue;
    const std::string frame = "frames[" + std::to_string(i) + "] (" + excerpt(manifest.frames[i].file) + "): ";
    if (s == 0) fail(frame + "dot frame but dot_spacing is 0");
    if (pattern.dot_offset_x < 0 || pattern.dot_offset_x >= s || pattern.dot_offset_y < 0 ||
        pattern.dot_offset_y >= s) {
      fail(frame + "dot_offset outside [0, dot_spacing)");
    }
    if (!seen.insert({pattern.dot_offset_x, pattern.dot_offset_y}).second) fail(frame + "repeated frame");
  }
  if (seen.size() != static_cast<std::size_t>(s) * static_cast<std::size_t>(s)) {
    fail("incomplete dot grid: " + std::to_string(seen.size()) + " of " + std::to_string(s * s) + " frames");
  }
}

}  // namespace rfrecon::capture
