// The "graycode" family's patterns, images, file names, manifest entries and completeness check.
#include "host/capture/graycode_patterns.h"

#include <cmath>
#include <cstdio>
#include <set>
#include <tuple>

#include <nlohmann/json.hpp>

#include "host/capture/dot_grid.h"
#include "host/core/errors.h"
#include "host/core/message_text.h"

namespace rfrecon::capture {

int gray_bits(int n) { return n <= 1 ? 0 : static_cast<int>(std::ceil(std::log2(static_cast<double>(n)))); }

bool gray_code_bit(int coordinate, int bit, int bits) {
  const int shift = bits - bit - 1;
  return (((coordinate >> shift) ^ (coordinate >> (shift + 1))) & 1) != 0;
}

bool is_gray(const Pattern& pattern) {
  return pattern.kind == pattern_kind::kGrayColumn || pattern.kind == pattern_kind::kGrayRow;
}

namespace {

Pattern plain(const char* kind) {
  Pattern pattern;
  pattern.kind = kind;
  return pattern;
}

void append_gray(std::vector<Pattern>& sequence, const char* kind, int bits) {
  for (int bit = 0; bit < bits; ++bit) {
    for (const bool inverse : {false, true}) {
      Pattern pattern = plain(kind);
      pattern.bit = bit;
      pattern.inverse = inverse;
      sequence.push_back(pattern);
    }
  }
}

void append_gray_pairs(std::vector<Pattern>& sequence, cv::Size projector_size) {
  append_gray(sequence, pattern_kind::kGrayColumn, gray_bits(projector_size.width));
  append_gray(sequence, pattern_kind::kGrayRow, gray_bits(projector_size.height));
}

class GraycodeFamily final : public PatternFamily {
 public:
  std::string name() const override { return kDefaultFamily; }
  std::string help() const override { return "Gray code of columns and rows with inverses, then an s x s dot grid"; }

  std::vector<Pattern> sequence(const ProtocolOptions& options) const override {
    check_dot_spacing(options.dot_spacing);
    std::vector<Pattern> sequence{plain(pattern_kind::kWhite), plain(pattern_kind::kBlack)};
    append_gray_pairs(sequence, options.projector_size);
    append_dot_grid(sequence, options.dot_spacing);
    return sequence;
  }

  cv::Mat render(const Pattern& pattern, const ProtocolOptions& options) const override {
    const cv::Size size = options.projector_size;
    cv::Mat image(size, CV_8UC1, cv::Scalar(0));
    if (pattern.kind == pattern_kind::kWhite) {
      image.setTo(255);
    } else if (is_gray(pattern)) {
      const bool columns = pattern.kind == pattern_kind::kGrayColumn;
      const int bits = gray_bits(columns ? size.width : size.height);
      for (int y = 0; y < size.height; ++y) {
        auto* row = image.ptr<unsigned char>(y);
        for (int x = 0; x < size.width; ++x) {
          row[x] = gray_code_bit(columns ? x : y, pattern.bit, bits) != pattern.inverse ? 255 : 0;
        }
      }
    } else if (pattern.kind == pattern_kind::kDot) {
      render_dot(pattern, options.dot_spacing, image);
    }
    return image;
  }

  std::string file_stem(const Pattern& pattern) const override {
    char stem[64];
    if (is_gray(pattern)) {
      std::snprintf(stem, sizeof stem, "%s_b%02d%s", pattern.kind.c_str(), pattern.bit, pattern.inverse ? "_inv" : "");
    } else if (pattern.kind == pattern_kind::kDot) {
      return dot_file_stem(pattern);
    } else {
      return pattern.kind;
    }
    return stem;
  }

  void write_entry(const Pattern& pattern, nlohmann::json& entry) const override {
    if (is_gray(pattern)) {
      entry["bit"] = pattern.bit;
      entry["inverse"] = pattern.inverse;
    } else if (pattern.kind == pattern_kind::kDot) {
      write_dot_entry(pattern, entry);
    }
  }

  void read_entry(const nlohmann::json& entry, const std::string& where, Pattern& pattern) const override {
    if (is_gray(pattern)) {
      pattern.bit = entry_int(entry, "bit", where);
      pattern.inverse = entry_bool(entry, "inverse", where);
    } else if (pattern.kind == pattern_kind::kDot) {
      read_dot_entry(entry, where, pattern);
    } else if (pattern.kind != pattern_kind::kWhite && pattern.kind != pattern_kind::kBlack) {
      throw InputError(where + ": pattern '" + excerpt(pattern.kind) +
                       "' is not one of the graycode family's (white, black, gray_col, gray_row, dot)");
    }
  }

  void validate(const CaptureManifest& manifest, const std::string& where) const override {
    const auto fail = [&](const std::string& what) { throw InputError(where + ": " + what); };
    std::set<std::tuple<int, int, bool>> gray_seen;
    const int column_bits = gray_bits(manifest.projector_size.width);
    const int row_bits = gray_bits(manifest.projector_size.height);
    for (std::size_t i = 0; i < manifest.frames.size(); ++i) {
      const auto& pattern = manifest.frames[i].pattern;
      const std::string frame = "frames[" + std::to_string(i) + "] (" + excerpt(manifest.frames[i].file) + "): ";
      if (is_gray(pattern)) {
        const bool columns = pattern.kind == pattern_kind::kGrayColumn;
        const int bits = columns ? column_bits : row_bits;
        if (pattern.bit < 0 || pattern.bit >= bits) {
          fail(frame + "Gray code bit " + std::to_string(pattern.bit) + " does not exist for a projector " +
               (columns ? "width of " + std::to_string(manifest.projector_size.width)
                        : "height of " + std::to_string(manifest.projector_size.height)) +
               " (" + std::to_string(bits) + " bits)");
        }
        if (!gray_seen.insert({columns ? 0 : 1, pattern.bit, pattern.inverse}).second) fail(frame + "repeated frame");
      }
    }
    if (gray_seen.size() != 2 * static_cast<std::size_t>(column_bits + row_bits)) {
      fail("incomplete Gray code: " + std::to_string(gray_seen.size()) + " of " +
           std::to_string(2 * (column_bits + row_bits)) + " frames for a " +
           std::to_string(manifest.projector_size.width) + "x" + std::to_string(manifest.projector_size.height) +
           " projector");
    }
    validate_dot_grid(manifest, where);
  }
};

}  // namespace

std::shared_ptr<const PatternFamily> graycode_family() { return std::make_shared<const GraycodeFamily>(); }

std::vector<Pattern> opencv_graycode_protocol(cv::Size projector_size) {
  check_projector_size(projector_size);
  std::vector<Pattern> sequence;
  append_gray_pairs(sequence, projector_size);
  sequence.push_back(plain(pattern_kind::kWhite));
  sequence.push_back(plain(pattern_kind::kBlack));
  return sequence;
}

}  // namespace rfrecon::capture
