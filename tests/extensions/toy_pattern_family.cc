// A pattern family registered from outside the library, through the front door only: "binary", plain binary code of
// columns and rows (no inverses), each bit decided against the midpoint of white and black, decoded on the host to
// whole-pixel correspondences. Linked into the CLI's own main as rfrecon_toy_cli, it shows that a new family is its
// two classes and their registrations (docs/architecture.md#extension-points).
#include <cstdio>
#include <memory>

#include <nlohmann/json.hpp>

#include "rfrecon/rfrecon.h"

namespace {

namespace transport = rfrecon::transport;

constexpr const char* kColumn = "binary_col";
constexpr const char* kRow = "binary_row";
enum ToyStep : int { kCodeFrame };

// ceil(log2(n)) bits code every coordinate of an axis of n pixels.
int bits_for(int n) {
  int bits = 0;
  while ((1 << bits) < n) ++bits;
  return bits;
}

bool is_code(const rfrecon::Pattern& pattern) { return pattern.kind == kColumn || pattern.kind == kRow; }

class BinaryPatterns : public rfrecon::PatternFamily {
 public:
  std::string name() const override { return "binary"; }
  std::string help() const override { return "test family: plain binary code of columns and rows"; }

  std::vector<rfrecon::Pattern> sequence(const rfrecon::ProtocolOptions& options) const override {
    if (options.dot_spacing != 0) throw rfrecon::InputError("the binary family takes no dot grid");
    std::vector<rfrecon::Pattern> sequence(2);
    sequence[1].kind = "black";
    for (const char* kind : {kColumn, kRow}) {
      const int n = kind == kColumn ? options.projector_size.width : options.projector_size.height;
      for (int bit = 0; bit < bits_for(n); ++bit) {
        rfrecon::Pattern pattern;
        pattern.kind = kind;
        pattern.bit = bit;
        sequence.push_back(pattern);
      }
    }
    return sequence;
  }

  cv::Mat render(const rfrecon::Pattern& pattern, const rfrecon::ProtocolOptions& options) const override {
    const cv::Size size = options.projector_size;
    cv::Mat image(size, CV_8UC1, cv::Scalar(pattern.kind == "white" ? 255 : 0));
    if (!is_code(pattern)) return image;
    const bool columns = pattern.kind == kColumn;
    const int shift = bits_for(columns ? size.width : size.height) - 1 - pattern.bit;
    for (int y = 0; y < size.height; ++y) {
      for (int x = 0; x < size.width; ++x) image.at<unsigned char>(y, x) = ((columns ? x : y) >> shift & 1) ? 255 : 0;
    }
    return image;
  }

  std::string file_stem(const rfrecon::Pattern& pattern) const override {
    if (!is_code(pattern)) return pattern.kind;
    char stem[32];
    std::snprintf(stem, sizeof stem, "%s_b%02d", pattern.kind.c_str(), pattern.bit);
    return stem;
  }

  void write_entry(const rfrecon::Pattern& pattern, nlohmann::json& entry) const override {
    if (is_code(pattern)) entry["bit"] = pattern.bit;
  }

  void read_entry(const nlohmann::json& entry, const std::string& where, rfrecon::Pattern& pattern) const override {
    if (is_code(pattern)) {
      pattern.bit = rfrecon::capture::entry_int(entry, "bit", where);
    } else if (pattern.kind != "white" && pattern.kind != "black") {
      throw rfrecon::InputError(where + ": not a binary family pattern");
    }
  }

  void validate(const rfrecon::Manifest& manifest, const std::string& where) const override {
    if (manifest.dot_spacing != 0) throw rfrecon::InputError(where + ": the binary family takes no dot grid");
    const auto expected = sequence(rfrecon::capture::protocol_options(manifest));
    if (manifest.frames.size() != expected.size()) throw rfrecon::InputError(where + ": not every binary pattern");
    for (std::size_t i = 0; i < expected.size(); ++i) {
      const auto& pattern = manifest.frames[i].pattern;
      if (pattern.kind != expected[i].kind || pattern.bit != expected[i].bit) {
        throw rfrecon::InputError(where + ": frames[" + std::to_string(i) + "] is not the binary sequence's");
      }
    }
  }
};

// Each camera pixel's column and row codes, one bit per frame; finish() makes the whole-pixel correspondences and
// one entry (white - black) at the coded projector pixel, as Gray-code-only captures have.
class BinaryAccumulator : public rfrecon::TransportAccumulator {
 public:
  explicit BinaryAccumulator(const transport::TransportSetup& setup) : t_(transport::make_empty_transport(setup)) {}

  void add(const rfrecon::TransportStep& step, const std::vector<cv::Mat>& frames, const cv::Mat& white,
           const cv::Mat& black) override {
    const cv::Mat frame = frames.at(0).depth() == CV_32F
                              ? frames.at(0)
                              : rfrecon::capture::linearize_samples(frames.at(0), t_.setup.samples);
    white_ = white;
    black_ = black;
    const bool columns = step.args[0] == 0;
    const int shift =
        bits_for(columns ? t_.setup.projector_size.width : t_.setup.projector_size.height) - 1 - step.args[1];
    auto& code = columns ? t_.pixel_x : t_.pixel_y;
    for (std::size_t c = 0; c < t_.camera_pixels(); ++c) {
      const float mid = 0.5f * (white.ptr<float>()[c] + black.ptr<float>()[c]);
      if (frame.ptr<float>()[c] > mid) code[c] |= 1u << shift;
    }
  }

  rfrecon::Transport finish() override {
    const cv::Size projector = t_.setup.projector_size;
    for (std::size_t c = 0; c < t_.camera_pixels(); ++c) {
      const float lit = white_.ptr<float>()[c] - black_.ptr<float>()[c];
      if (!(lit > t_.setup.thresholds.black)) {
        t_.flags[c] = transport::kFlagShadow;
      } else if (t_.pixel_x[c] >= static_cast<unsigned>(projector.width) ||
                 t_.pixel_y[c] >= static_cast<unsigned>(projector.height)) {
        t_.flags[c] = transport::kFlagOutOfRange;
      } else {
        t_.flags[c] = transport::kFlagValid;
        t_.correspondence[2 * c] = static_cast<float>(t_.pixel_x[c]);
        t_.correspondence[2 * c + 1] = static_cast<float>(t_.pixel_y[c]);
        const std::size_t row = c * static_cast<std::size_t>(t_.k());
        t_.indices[row] = static_cast<int>(t_.pixel_y[c]) * projector.width + static_cast<int>(t_.pixel_x[c]);
        t_.weights[row] = lit;
        t_.direct_energy[c] = lit;
      }
    }
    return std::move(t_);
  }

 private:
  rfrecon::Transport t_;
  cv::Mat white_;
  cv::Mat black_;
};

class BinaryDecoding : public rfrecon::DecodingFamily {
 public:
  std::string name() const override { return "binary"; }

  std::vector<rfrecon::TransportStep> plan(const rfrecon::Manifest& manifest) const override {
    std::vector<rfrecon::TransportStep> steps;
    for (std::size_t i = 0; i < manifest.frames.size(); ++i) {
      const auto& pattern = manifest.frames[i].pattern;
      if (is_code(pattern))
        steps.push_back({kCodeFrame, {i}, {pattern.kind == kColumn ? 0 : 1, pattern.bit}, "decode"});
    }
    steps.emplace_back();
    return steps;
  }

  std::vector<rfrecon::cl::ProgramRequest> programs(const transport::TransportSetup&,
                                                    rfrecon::cl::KernelEntry) const override {
    return {};
  }

  std::unique_ptr<rfrecon::TransportAccumulator> make_reference(const transport::TransportSetup& setup) const override {
    return std::make_unique<BinaryAccumulator>(setup);
  }

  // No kernels: the host decodes each device's block of rows.
  std::unique_ptr<rfrecon::TransportAccumulator> make_device(const transport::TransportSetup& setup,
                                                             rfrecon::cl::DeviceContext&, rfrecon::cl::ProgramCache&,
                                                             rfrecon::cl::KernelEntry,
                                                             rfrecon::Transport) const override {
    return make_reference(setup);
  }

  std::unique_ptr<rfrecon::TransportRefinement> refinement(const transport::TransportSetup&, const cv::Mat&,
                                                           const cv::Mat&) const override {
    return nullptr;
  }
};

[[maybe_unused]] const bool kBinaryFamilyRegistered = [] {
  rfrecon::register_pattern_family(std::make_shared<const BinaryPatterns>());
  rfrecon::register_decoding_family(std::make_shared<const BinaryDecoding>());
  return true;
}();

}  // namespace
