// A capture's projector pattern sequence: its patterns, the options that make one, and their images, through the
// pattern family the capture uses (host/capture/pattern_family.h).
#pragma once

#include <map>
#include <string>
#include <vector>

#include <opencv2/core.hpp>

namespace rfrecon::capture {

// The manifest's names of the patterns the built-in families project. Every family has one white and one black
// frame; the other kinds are the family's own (families may share them: a phase-shifting family unwraps with Gray
// code).
namespace pattern_kind {
inline constexpr const char* kWhite = "white";
inline constexpr const char* kBlack = "black";
inline constexpr const char* kGrayColumn = "gray_col";
inline constexpr const char* kGrayRow = "gray_row";
inline constexpr const char* kDot = "dot";
}  // namespace pattern_kind

// One projector image of the sequence.
struct Pattern {
  std::string kind = pattern_kind::kWhite;
  int bit = -1;           // code patterns: bit index, 0 = most significant
  bool inverse = false;   // code patterns: the inverted image of the pair
  int dot_offset_x = -1;  // dot grid: lit pixels have x % spacing == dot_offset_x ...
  int dot_offset_y = -1;  // ... and y % spacing == dot_offset_y
  int level = 0;          // phase steps: the frequency, 0 = the finest period (host/capture/phase_patterns.h)
};

// The family of captures whose manifest names none: Gray code with a dot grid (host/capture/graycode_patterns.h).
inline constexpr const char* kDefaultFamily = "graycode";

struct ProtocolOptions {
  cv::Size projector_size;  // projector resolution in pixels
  int dot_spacing = 0;      // s of the s x s dot-grid scan after the family's patterns; 0 = no dot grid
  std::string family = kDefaultFamily;
  std::map<std::string, int> parameters{};  // the family's parameters given (PatternFamily::parameters); others default
};

// The sequence of `options.family` (throws InputError for an unknown family, a projector under 2x2 or an option the
// family does not take).
std::vector<Pattern> make_protocol(const ProtocolOptions& options);

// The projector image of a pattern of `options.family`: CV_8UC1, 255 = lit, 0 = dark.
cv::Mat render_pattern(const Pattern& pattern, const ProtocolOptions& options);

// Throws InputError unless the projector is at least 2x2 and within host/core/limits.h.
void check_projector_size(cv::Size projector_size);

}  // namespace rfrecon::capture
