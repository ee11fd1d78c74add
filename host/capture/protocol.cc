// Pattern sequence generation for the capture protocol.
#include "host/capture/protocol.h"

#include <cmath>

#include "host/core/errors.h"
#include "host/core/limits.h"
#include "host/core/message_text.h"

namespace rfrecon::capture {

int gray_bits(int n) { return n <= 1 ? 0 : static_cast<int>(std::ceil(std::log2(static_cast<double>(n)))); }

bool gray_code_bit(int coordinate, int bit, int bits) {
  const int shift = bits - bit - 1;
  return (((coordinate >> shift) ^ (coordinate >> (shift + 1))) & 1) != 0;
}

namespace {
void append_gray(std::vector<Pattern>& sequence, PatternKind kind, int bits) {
  for (int bit = 0; bit < bits; ++bit) {
    for (const bool inverse : {false, true}) {
      Pattern pattern;
      pattern.kind = kind;
      pattern.bit = bit;
      pattern.inverse = inverse;
      sequence.push_back(pattern);
    }
  }
}

void append_gray_pairs(std::vector<Pattern>& sequence, cv::Size projector_size) {
  append_gray(sequence, PatternKind::kGrayColumn, gray_bits(projector_size.width));
  append_gray(sequence, PatternKind::kGrayRow, gray_bits(projector_size.height));
}

Pattern plain(PatternKind kind) {
  Pattern pattern;
  pattern.kind = kind;
  return pattern;
}

void check_size(cv::Size projector_size) {
  if (projector_size.width < 2 || projector_size.height < 2) {
    throw InputError("projector size must be at least 2x2, got " + std::to_string(projector_size.width) + "x" +
                     std::to_string(projector_size.height));
  }
  check_image_size(projector_size, "projector");
}
}  // namespace

std::vector<Pattern> make_protocol(const ProtocolOptions& options) {
  check_size(options.projector_size);
  if (options.dot_spacing < 0 || options.dot_spacing == 1 || options.dot_spacing > kMaxDotSpacing) {
    throw InputError("dot spacing must be 0 (no dot grid) or 2 to " + std::to_string(kMaxDotSpacing) + ", got " +
                     std::to_string(options.dot_spacing));
  }
  std::vector<Pattern> sequence{plain(PatternKind::kWhite), plain(PatternKind::kBlack)};
  append_gray_pairs(sequence, options.projector_size);
  for (int oy = 0; oy < options.dot_spacing; ++oy) {
    for (int ox = 0; ox < options.dot_spacing; ++ox) {
      Pattern dot = plain(PatternKind::kDot);
      dot.dot_offset_x = ox;
      dot.dot_offset_y = oy;
      sequence.push_back(dot);
    }
  }
  return sequence;
}

std::vector<Pattern> opencv_graycode_protocol(cv::Size projector_size) {
  check_size(projector_size);
  std::vector<Pattern> sequence;
  append_gray_pairs(sequence, projector_size);
  sequence.push_back(plain(PatternKind::kWhite));
  sequence.push_back(plain(PatternKind::kBlack));
  return sequence;
}

cv::Mat render_pattern(const Pattern& pattern, cv::Size projector_size, int dot_spacing) {
  cv::Mat image(projector_size, CV_8UC1, cv::Scalar(0));
  switch (pattern.kind) {
    case PatternKind::kWhite:
      image.setTo(255);
      break;
    case PatternKind::kBlack:
      break;
    case PatternKind::kGrayColumn:
    case PatternKind::kGrayRow: {
      const bool columns = pattern.kind == PatternKind::kGrayColumn;
      const int bits = gray_bits(columns ? projector_size.width : projector_size.height);
      for (int y = 0; y < projector_size.height; ++y) {
        auto* row = image.ptr<unsigned char>(y);
        for (int x = 0; x < projector_size.width; ++x) {
          const bool lit = gray_code_bit(columns ? x : y, pattern.bit, bits) != pattern.inverse;
          row[x] = lit ? 255 : 0;
        }
      }
      break;
    }
    case PatternKind::kDot:
      for (int y = pattern.dot_offset_y; y < projector_size.height; y += dot_spacing) {
        for (int x = pattern.dot_offset_x; x < projector_size.width; x += dot_spacing) {
          image.at<unsigned char>(y, x) = 255;
        }
      }
      break;
  }
  return image;
}

const char* to_string(PatternKind kind) {
  switch (kind) {
    case PatternKind::kWhite:
      return "white";
    case PatternKind::kBlack:
      return "black";
    case PatternKind::kGrayColumn:
      return "gray_col";
    case PatternKind::kGrayRow:
      return "gray_row";
    case PatternKind::kDot:
      return "dot";
  }
  return "unknown";
}

PatternKind pattern_kind_from_string(const std::string& name) {
  for (const auto kind :
       {PatternKind::kWhite, PatternKind::kBlack, PatternKind::kGrayColumn, PatternKind::kGrayRow, PatternKind::kDot}) {
    if (name == to_string(kind)) return kind;
  }
  throw InputError("unknown pattern kind '" + excerpt(name) + "' (expected white, black, gray_col, gray_row or dot)");
}

}  // namespace rfrecon::capture
