// The "phase" family's patterns, images, file names, manifest entries and completeness check.
#include "host/capture/phase_patterns.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <set>
#include <stdexcept>
#include <string>
#include <tuple>

#include <nlohmann/json.hpp>

#include "host/capture/dot_grid.h"
#include "host/capture/graycode_patterns.h"
#include "host/core/errors.h"
#include "host/core/message_text.h"

namespace rfrecon::capture {

double phase_shift_radians(int step, int steps, PhaseConvention convention) {
  const double pi = 3.14159265358979323846;
  return (convention.reversed ? -2.0 : 2.0) * pi * step / steps - pi * convention.origin_degrees / 180.0;
}

double phase_pattern_level(double x, double period, int step, int steps, PhaseConvention convention) {
  const double two_pi = 2.0 * 3.14159265358979323846;
  return 0.5 + 0.5 * std::cos(two_pi * x / period - phase_shift_radians(step, steps, convention));
}

int phase_order(int x, double period, int unit) { return static_cast<int>(std::floor(2.0 * x / (unit * period))); }

int phase_order_bits(int n, double period, int unit) { return gray_bits(phase_order(n - 1, period, unit) + 1); }

std::vector<double> phase_periods(int n, double period, int ratio, bool spanning_last) {
  std::vector<double> periods{period};
  if (ratio == 0) return periods;
  if (ratio < 2) throw std::invalid_argument("phase_periods: ratio " + std::to_string(ratio) + " under 2");
  if (spanning_last) {
    while (periods.back() < n) periods.push_back(periods.back() * ratio);
    return periods;
  }
  while (periods.back() * (ratio - 1) < n) periods.push_back(periods.back() * ratio);
  periods.push_back(n + periods.back());
  return periods;
}

std::vector<int> phase_heterodyne_fringes(int fringes, int beat) {
  if (beat == 0) return {};
  if (beat == 1) return {fringes, fringes - 1};
  return {fringes, fringes - beat, fringes - 2 * beat + 1};
}

std::vector<double> phase_periods(const ProtocolOptions& options, bool columns) {
  const PatternFamily& family = pattern_family("phase");
  const int n = columns ? options.projector_size.width : options.projector_size.height;
  const int fringes = family_parameter(family, options, kPhaseFringes);
  const std::vector<int> beats = phase_heterodyne_fringes(fringes, family_parameter(family, options, kPhaseHeterodyne));
  if (!beats.empty()) {
    std::vector<double> periods(beats.size());
    std::transform(beats.begin(), beats.end(), periods.begin(), [n](int f) { return static_cast<double>(n) / f; });
    return periods;
  }
  return phase_periods(n,
                       fringes > 0 ? static_cast<double>(n) / fringes
                                   : static_cast<double>(family_parameter(family, options, kPhasePeriod)),
                       family_parameter(family, options, kPhaseRatio),
                       family_parameter(family, options, kPhaseCoarsest) == 1);
}

namespace {

bool is_phase(const Pattern& p) { return p.kind == pattern_kind::kPhaseColumn || p.kind == pattern_kind::kPhaseRow; }
bool is_order(const Pattern& p) { return p.kind == pattern_kind::kOrderColumn || p.kind == pattern_kind::kOrderRow; }
bool on_columns(const Pattern& p) {
  return p.kind == pattern_kind::kPhaseColumn || p.kind == pattern_kind::kOrderColumn;
}

// The order code of a capture: its unit in half periods and whether its patterns have inverses.
struct OrderCode {
  int unit = 1;
  bool inverses = true;
};

class PhaseFamily final : public PatternFamily {
 public:
  std::string name() const override { return "phase"; }
  std::string help() const override {
    return "N-step phase shifting of columns and rows, unwrapped by a Gray code of half periods, by longer periods or "
           "by heterodyne beats, then an s x s dot grid";
  }
  std::vector<FamilyParameter> parameters() const override {
    return {{kPhaseSteps, 4, 3, 64, "phase: steps N of each axis's sinusoid"},
            {kPhasePeriod, 16, 4, 4096, "phase: period of the sinusoids, projector pixels"},
            {kPhaseRatio, 0, 2, 64,
             "phase: unwrap by sinusoids of periods P, P R, P R^2, ... (R); 0 = by a Gray code of half periods",
             "Gray code of half periods"},
            {kPhaseFringes, 0, 1, 1024, "phase: F periods across each axis instead of P pixels; 0 = P", "the period P"},
            {kPhaseHeterodyne, 0, 1, 512,
             "phase: unwrap by the beats of F, F - 1 (B = 1) or F, F - B, F - 2 B + 1 fringes (B); 0 = no beats",
             "no beats"},
            {kPhaseCoarsest, 0, 0, 1,
             "phase: 1 = the longer periods end at the first that spans the axis (0: one more, axis + the last)"},
            {kPhaseOrigin, 0, 0, 359, "phase: phase of step 0 at projector coordinate 0, degrees"},
            {kPhaseReversed, 0, 0, 1, "phase: 1 = step k shifts the sinusoid by +2 pi k / N rather than -2 pi k / N"},
            {kOrderUnit, 1, 1, 2, "phase: the order code counts half periods (1) or whole periods (2)"},
            {kOrderInverses, 1, 0, 1, "phase: 0 = the order code has no inverse patterns"}};
  }

  PhaseConvention convention(const ProtocolOptions& options) const {
    return {family_parameter(*this, options, kPhaseOrigin), family_parameter(*this, options, kPhaseReversed) == 1};
  }

  OrderCode order_code(const ProtocolOptions& options) const {
    return {family_parameter(*this, options, kOrderUnit), family_parameter(*this, options, kOrderInverses) == 1};
  }

  // Whether the order code unwraps (neither longer periods nor beats); throws InputError starting with `where` for
  // parameters that do not go together or a period under 4 projector pixels.
  bool by_order(const ProtocolOptions& options, const std::string& where) const {
    const int ratio = family_parameter(*this, options, kPhaseRatio);
    const int fringes = family_parameter(*this, options, kPhaseFringes);
    const int beat = family_parameter(*this, options, kPhaseHeterodyne);
    if (beat > 0 && (fringes == 0 || ratio != 0)) {
      throw InputError(where + ": phase_heterodyne needs phase_fringes and no phase_ratio");
    }
    const std::vector<int> beats = phase_heterodyne_fringes(fringes, beat);
    if (!beats.empty() && beats.back() < 1) {
      throw InputError(where + ": phase_heterodyne " + std::to_string(beat) + " on " + std::to_string(fringes) +
                       " fringes leaves fewer than 1 (fringes at least 2 B)");
    }
    for (const bool columns : {true, false}) {
      if (phase_periods(options, columns).front() < 4.0) {
        throw InputError(where + ": " + std::to_string(fringes) + " fringes across " +
                         std::to_string(columns ? options.projector_size.width : options.projector_size.height) +
                         " projector pixels make periods under 4 pixels");
      }
    }
    return ratio == 0 && beat == 0;
  }

  std::vector<Pattern> sequence(const ProtocolOptions& options) const override {
    check_dot_spacing(options.dot_spacing);
    const int steps = family_parameter(*this, options, kPhaseSteps);
    const bool ordered = by_order(options, "phase");
    const OrderCode order = order_code(options);
    std::vector<Pattern> sequence(2);
    sequence[1].kind = pattern_kind::kBlack;
    for (const bool columns : {true, false}) {
      const int n = columns ? options.projector_size.width : options.projector_size.height;
      const double period = phase_periods(options, columns).front();
      for (int bit = 0; ordered && bit < phase_order_bits(n, period, order.unit); ++bit) {
        for (const bool inverse : {false, true}) {
          if (inverse && !order.inverses) continue;
          Pattern pattern;
          pattern.kind = columns ? pattern_kind::kOrderColumn : pattern_kind::kOrderRow;
          pattern.bit = bit;
          pattern.inverse = inverse;
          sequence.push_back(pattern);
        }
      }
      // Coarsest period first: the order in which they unwrap.
      for (int level = static_cast<int>(phase_periods(options, columns).size()) - 1; level >= 0; --level) {
        for (int step = 0; step < steps; ++step) {
          Pattern pattern;
          pattern.kind = columns ? pattern_kind::kPhaseColumn : pattern_kind::kPhaseRow;
          pattern.bit = step;
          pattern.level = level;
          sequence.push_back(pattern);
        }
      }
    }
    append_dot_grid(sequence, options.dot_spacing);
    return sequence;
  }

  cv::Mat render(const Pattern& pattern, const ProtocolOptions& options) const override {
    const cv::Size size = options.projector_size;
    cv::Mat image(size, CV_8UC1, cv::Scalar(pattern.kind == pattern_kind::kWhite ? 255 : 0));
    if (pattern.kind == pattern_kind::kDot) render_dot(pattern, options.dot_spacing, image);
    if (!is_phase(pattern) && !is_order(pattern)) return image;
    const int steps = family_parameter(*this, options, kPhaseSteps);
    const bool columns = on_columns(pattern);
    const int n = columns ? size.width : size.height;
    const OrderCode order = order_code(options);
    const std::vector<double> periods = phase_periods(options, columns);
    const double period = periods.front();
    const int bits = phase_order_bits(n, period, order.unit);
    const double level_period = periods.at(pattern.level);
    for (int y = 0; y < size.height; ++y) {
      auto* row = image.ptr<unsigned char>(y);
      for (int x = 0; x < size.width; ++x) {
        const int coordinate = columns ? x : y;
        if (is_phase(pattern)) {
          row[x] = static_cast<unsigned char>(std::lround(
              255.0 * phase_pattern_level(coordinate, level_period, pattern.bit, steps, convention(options))));
        } else {
          row[x] = gray_code_bit(phase_order(coordinate, period, order.unit), pattern.bit, bits) != pattern.inverse
                       ? 255
                       : 0;
        }
      }
    }
    return image;
  }

  std::string file_stem(const Pattern& pattern) const override {
    char stem[64];
    if (is_phase(pattern) && pattern.level > 0) {
      std::snprintf(stem, sizeof stem, "%s_l%d_s%02d", pattern.kind.c_str(), pattern.level, pattern.bit);
    } else if (is_phase(pattern)) {
      std::snprintf(stem, sizeof stem, "%s_s%02d", pattern.kind.c_str(), pattern.bit);
    } else if (is_order(pattern)) {
      std::snprintf(stem, sizeof stem, "%s_b%02d%s", pattern.kind.c_str(), pattern.bit, pattern.inverse ? "_inv" : "");
    } else if (pattern.kind == pattern_kind::kDot) {
      return dot_file_stem(pattern);
    } else {
      return pattern.kind;
    }
    return stem;
  }

  void write_entry(const Pattern& pattern, nlohmann::json& entry) const override {
    if (is_phase(pattern)) entry["step"] = pattern.bit;
    if (is_phase(pattern) && pattern.level > 0) entry["level"] = pattern.level;
    if (is_order(pattern)) {
      entry["bit"] = pattern.bit;
      entry["inverse"] = pattern.inverse;
    }
    if (pattern.kind == pattern_kind::kDot) write_dot_entry(pattern, entry);
  }

  void read_entry(const nlohmann::json& entry, const std::string& where, Pattern& pattern) const override {
    if (is_phase(pattern)) {
      pattern.bit = entry_int(entry, "step", where);
      pattern.level = entry.contains("level") ? entry_int(entry, "level", where) : 0;
    } else if (is_order(pattern)) {
      pattern.bit = entry_int(entry, "bit", where);
      pattern.inverse = entry.contains("inverse") && entry_bool(entry, "inverse", where);
    } else if (pattern.kind == pattern_kind::kDot) {
      read_dot_entry(entry, where, pattern);
    } else if (pattern.kind != pattern_kind::kWhite && pattern.kind != pattern_kind::kBlack) {
      throw InputError(where + ": pattern '" + excerpt(pattern.kind) +
                       "' is not one of the phase family's (white, black, phase_col, phase_row, order_col, "
                       "order_row, dot)");
    }
  }

  void validate(const CaptureManifest& manifest, const std::string& where) const override {
    const auto fail = [&](const std::string& what) { throw InputError(where + ": " + what); };
    validate_dot_grid(manifest, where);
    const ProtocolOptions options = protocol_options(manifest);
    const int steps = family_parameter(*this, options, kPhaseSteps);
    const bool ordered = by_order(options, where);
    const OrderCode order = order_code(options);
    std::set<std::tuple<std::string, int, bool, int>> seen;
    for (std::size_t i = 0; i < manifest.frames.size(); ++i) {
      const Pattern& pattern = manifest.frames[i].pattern;
      if (!is_phase(pattern) && !is_order(pattern)) continue;
      const std::string frame = "frames[" + std::to_string(i) + "] (" + excerpt(manifest.frames[i].file) + "): ";
      const int n = on_columns(pattern) ? manifest.projector_size.width : manifest.projector_size.height;
      if (is_order(pattern) && !ordered) {
        fail(frame + "an order code frame, but longer periods or beats unwrap (phase_ratio, phase_heterodyne)");
      }
      if (is_order(pattern) && pattern.inverse && !order.inverses) {
        fail(frame + "an inverse order pattern, but order_inverses is 0");
      }
      const int count = is_phase(pattern)
                            ? steps
                            : phase_order_bits(n, phase_periods(options, on_columns(pattern)).front(), order.unit);
      if (pattern.bit < 0 || pattern.bit >= count) {
        fail(frame + (is_phase(pattern) ? "step " : "order bit ") + std::to_string(pattern.bit) + " outside 0 to " +
             std::to_string(count - 1));
      }
      const int levels = static_cast<int>(phase_periods(options, on_columns(pattern)).size());
      if (pattern.level < 0 || pattern.level >= levels) {
        fail(frame + "level " + std::to_string(pattern.level) + " outside 0 to " + std::to_string(levels - 1));
      }
      if (!seen.insert({pattern.kind, pattern.bit, pattern.inverse, pattern.level}).second) {
        fail(frame + "repeated frame");
      }
    }
    const std::size_t expected =
        sequence(options).size() - 2 - static_cast<std::size_t>(manifest.dot_spacing * manifest.dot_spacing);
    if (seen.size() != expected) {
      fail("incomplete phase sequence: " + std::to_string(seen.size()) + " of " + std::to_string(expected) +
           " phase and order frames for " + std::to_string(steps) + " steps of each period");
    }
  }
};

}  // namespace

std::shared_ptr<const PatternFamily> phase_family() { return std::make_shared<const PhaseFamily>(); }

}  // namespace rfrecon::capture
