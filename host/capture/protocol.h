// The projector pattern sequence of a capture: white, black, Gray code (columns, rows) with inverses, dot grid.
#pragma once

#include <string>
#include <vector>

#include <opencv2/core.hpp>

namespace rfrecon::capture {

enum class PatternKind { kWhite, kBlack, kGrayColumn, kGrayRow, kDot };

// One projector image of the sequence.
struct Pattern {
  PatternKind kind = PatternKind::kWhite;
  int bit = -1;           // Gray code: bit index, 0 = most significant
  bool inverse = false;   // Gray code: the inverted image of the pair
  int dot_offset_x = -1;  // dot grid: lit pixels have x % spacing == dot_offset_x ...
  int dot_offset_y = -1;  // ... and y % spacing == dot_offset_y
};

inline constexpr int kMaxDotSpacing = 64;  // s x s = 4096 dot frames at most

struct ProtocolOptions {
  cv::Size projector_size;  // projector resolution in pixels
  int dot_spacing = 0;      // s of the s x s dot-grid scan; 0 = no dot grid (Gray code only)
};

// Number of Gray code bits for a projector axis of n pixels: ceil(log2(n)), as OpenCV's GrayCodePattern.
int gray_bits(int n);

// The standard rfrecon protocol: white, black, then for each column bit (MSB first) the pattern and its inverse,
// then the same for rows (OpenCV GrayCodePattern order), then dot frames with offset (ox, oy), ox fastest.
std::vector<Pattern> make_protocol(const ProtocolOptions& options);

// OpenCV GrayCodePattern's capture order: its Gray code images (columns then rows, each pattern then inverse),
// then one white and one black frame.
std::vector<Pattern> opencv_graycode_protocol(cv::Size projector_size);

// The projector image of a pattern: CV_8UC1, 255 = lit, 0 = dark. Identical to OpenCV GrayCodePattern::generate()
// for Gray code frames.
cv::Mat render_pattern(const Pattern& pattern, cv::Size projector_size, int dot_spacing);

// The Gray code value of projector coordinate `coordinate` for bit `bit` (MSB first) of an axis with `bits` bits.
bool gray_code_bit(int coordinate, int bit, int bits);

// Stable names for manifests and logs: "white", "black", "gray_col", "gray_row", "dot".
const char* to_string(PatternKind kind);
PatternKind pattern_kind_from_string(const std::string& name);  // throws InputError on an unknown name

}  // namespace rfrecon::capture
