// The phase family: unwrapping recovers every projector coordinate from its wrapped phase and half-period order (off
// by one at its edge included). On the synthetic rig (a plane, 4 steps of period 16) its sub-pixel correspondences
// are within 0.1 projector pixel RMS of the truth in focus, and under a projector defocus of sigma 2.5 px, which washes
// out Gray code's finest stripes, less than half Gray code's error on the same pixels. With a dot grid after the
// phases, the integration and the fusion run on them. Another tool's conventions and heterodyne beats decode as
// precisely as the order code.
#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>
#include <tuple>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>

#include "host/capture/phase_patterns.h"
#include "host/transport/phase_decoding.h"
#include "host/transport/transport_file.h"
#include "tests/common/run_cli.h"
#include "tests/common/temp_dir.h"

namespace rfrecon::transport {
namespace {

namespace fs = std::filesystem;
constexpr double kPi = 3.14159265358979323846;

TEST(PhaseUnwrapTest, RecoversEveryCoordinateFromPhaseAndAnOrderOffByOneAtItsEdge) {
  for (const int period : {4, 7, 16, 30}) {
    for (double u = -0.5; u < 200.0; u += 0.0625) {
      const double theta = std::remainder(2.0 * kPi * u / period, 2.0 * kPi);  // as atan2 gives it
      const int pixel = static_cast<int>(std::lround(u));
      const int order = capture::phase_order(std::max(pixel, 0), period);
      EXPECT_NEAR(unwrap_phase(theta, order, period), u, 1e-9) << "P " << period << " u " << u;
      // A pixel within a tenth of a period of its half period's edge may read the neighbouring order.
      const double in_half = u + 0.5 - order * 0.5 * period;
      if (in_half < 0.1 * period && order > 0) {
        EXPECT_NEAR(unwrap_phase(theta, order - 1, period), u, 1e-9);
      }
      if (in_half > 0.4 * period) {
        EXPECT_NEAR(unwrap_phase(theta, order + 1, period), u, 1e-9);
      }
      EXPECT_NEAR(unwrap_phase(theta + 0.2 * kPi, order, period), u + 0.1 * period, 1e-9);  // phase error carried
    }
  }
}

TEST(PhaseUnwrapTest, LongerPeriodsUnwrapTheFinestFromTheCoarsestEstimate) {
  // Each period at most R times the one before; the coarsest over the axis plus the next one.
  for (const auto& [n, period, ratio] :
       {std::tuple{1024, 16, 8}, std::tuple{1280, 16, 4}, std::tuple{12, 4, 2}, std::tuple{800, 7, 64}}) {
    const auto periods = capture::phase_periods(n, period, ratio);
    ASSERT_GE(periods.size(), 2U);
    EXPECT_EQ(periods.front(), period);
    for (std::size_t k = 1; k < periods.size(); ++k) EXPECT_LE(periods[k], ratio * periods[k - 1]) << n;
    EXPECT_GE(periods.back(), n + periods[periods.size() - 2]) << n;
    // Every coordinate of the axis unwraps level by level to the truth while each level's phase is off by less than
    // 1 / (2 R) of its period: here 0.8 of that.
    const double error = 0.4 / ratio;  // periods
    for (double u = -0.5; u < n - 0.5; u += 0.37) {
      double estimate = 0.5 * (n - 1);
      for (auto p = periods.rbegin(); p != periods.rend(); ++p) {
        const double theta = std::remainder(2.0 * kPi * (u / *p + error), 2.0 * kPi);
        estimate = unwrap_near(theta, estimate, *p);
      }
      EXPECT_NEAR(estimate, u + error * period, 1e-9) << "n " << n << " u " << u;
    }
  }
  EXPECT_EQ(capture::phase_periods(640, 16, 0), std::vector<double>{16});
  // Another tool's ladder ends at the first period that spans the axis: fringe counts 64, 8, 1 of 1280 pixels.
  EXPECT_EQ(capture::phase_periods(1280, 20, 8, true), (std::vector<double>{20, 160, 1280}));
  EXPECT_EQ(capture::phase_periods(1000, 20, 8, true), (std::vector<double>{20, 160, 1280}));
}

// Heterodyne beats: 70, 64 and 59 fringes across 1280 pixels (B = 6) and 20, 19 (B = 1) across 80. Every coordinate
// unwraps to the truth while each phase is off by up to 0.8 of the bound, alternating in sign (the worst case): the
// beat of the beats, t0 - 2 t1 + t2, is then off by 4 e turns of the axis, under half the beat's period (e < 1 / (8
// B)), and the beat by 2 e of its period, under half the finest one (e < B / (4 F)). Every pattern repeats after the
// axis, so within that error of the axis's end a pixel may come out a whole axis off: outside it, where it is flagged.
TEST(PhaseUnwrapTest, HeterodyneBeatsUnwrapEveryCoordinate) {
  for (const auto& [n, fringes, beat] : {std::tuple{1280, 70, 6}, std::tuple{80, 20, 1}}) {
    const std::vector<int> counts = capture::phase_heterodyne_fringes(fringes, beat);
    ASSERT_EQ(counts.size(), beat == 1 ? 2U : 3U);
    EXPECT_EQ(counts.back(), beat == 1 ? fringes - 1 : fringes - 2 * beat + 1);
    const double bound =
        beat == 1 ? 1.0 / (4.0 * fringes) : std::min(1.0 / (8.0 * beat), beat / (4.0 * fringes));  // turns
    const double error = 0.8 * bound;
    const double band = (beat == 1 ? 2.0 : 4.0) * error * n;  // pixels at the end that may wrap
    std::size_t wrapped = 0;
    for (double u = -0.4; u < n - 0.5; u += 0.37) {
      double turns[3];
      for (std::size_t l = 0; l < counts.size(); ++l) {
        const double t = u * counts[l] / n + (l % 2 == 0 ? error : -error);
        turns[l] = t - std::floor(t);
      }
      const double estimate = heterodyne_estimate(turns, counts, n);
      const double period = static_cast<double>(n) / fringes;
      const double u_found = unwrap_near(2.0 * kPi * turns[0], estimate, period);
      if (std::abs(u_found - (u + error * period)) < 1e-9) continue;
      ++wrapped;
      EXPECT_NEAR(u_found, u + error * period - n, 1e-9) << "n " << n << " u " << u;
      EXPECT_GT(u, n - 0.5 - band) << "n " << n;
    }
    EXPECT_LT(static_cast<double>(wrapped), band / 0.37 + 1.0);
  }
}

TEST(PhaseFamilyTest, PatternsCommandWritesTheSequenceWithItsParameters) {
  testing::TempDir dir("phase_patterns");
  const fs::path out = dir.path() / "patterns";
  const auto written = testing::run_cli(
      "-q patterns --family phase --phase-steps 5 --phase-period 20 --projector 64x40 -o " + out.string());
  ASSERT_EQ(written.exit_code, 0) << written.output;
  nlohmann::json manifest;
  std::ifstream(out / "manifest.json") >> manifest;
  EXPECT_EQ(manifest.at("family"), "phase");
  EXPECT_EQ(manifest.at("parameters").at("phase_steps"), 5);
  EXPECT_EQ(manifest.at("parameters").at("phase_period"), 20);
  // White, black; columns: ceil(log2(ceil(128 / 20))) = 3 order pairs and 5 steps; rows: ceil(log2(4)) = 2 pairs.
  ASSERT_EQ(manifest.at("frames").size(), 2U + 6U + 5U + 4U + 5U);
  const auto& step = manifest.at("frames").at(8);  // the first column step
  ASSERT_EQ(step.at("pattern"), "phase_col");
  const cv::Mat image = cv::imread((out / step.at("file").get<std::string>()).string(), cv::IMREAD_GRAYSCALE);
  for (int x = 0; x < image.cols; ++x) {
    EXPECT_NEAR(image.at<unsigned char>(3, x), 127.5 + 127.5 * std::cos(2.0 * kPi * x / 20.0), 0.5) << x;
  }
  const auto wrong = testing::run_cli("patterns --phase-steps 5 --projector 64x40 -o " + (dir.path() / "g").string());
  EXPECT_EQ(wrong.exit_code, 3) << wrong.output;  // graycode has no such parameter: nothing written
  EXPECT_NE(wrong.output.find("parameter 'phase_steps' is not one of the graycode family's"), std::string::npos)
      << wrong.output;
  EXPECT_FALSE(fs::exists(dir.path() / "g"));
  const auto range =
      testing::run_cli("patterns --family phase --phase-steps 2 --projector 64x40 -o " + (dir.path() / "r").string());
  EXPECT_EQ(range.exit_code, 2) << range.output;  // under the documented 3
  const auto ratio_one =
      testing::run_cli("patterns --family phase --phase-ratio 1 --projector 64x40 -o " + (dir.path() / "r").string());
  EXPECT_EQ(ratio_one.exit_code, 2) << ratio_one.output;  // 0 or 2 to 64
}

TEST(PhaseFamilyTest, LongerPeriodsReplaceTheOrderCodeInTheSequenceAndManifest) {
  testing::TempDir dir("phase_ratio");
  const fs::path out = dir.path() / "patterns";
  const auto written = testing::run_cli(
      "-q patterns --family phase --phase-steps 3 --phase-period 8 --phase-ratio 4 "
      "--projector 64x40 -o " +
      out.string());
  ASSERT_EQ(written.exit_code, 0) << written.output;
  nlohmann::json manifest;
  std::ifstream(out / "manifest.json") >> manifest;
  EXPECT_EQ(manifest.at("parameters").at("phase_ratio"), 4);
  // Columns: periods 8, 32, 96 (32 * 3 >= 64, then 64 + 32); rows: 8, 32, 72. Three steps each, no order frame.
  ASSERT_EQ(manifest.at("frames").size(), 2U + 9U + 9U);
  const auto& coarsest = manifest.at("frames").at(2);  // coarsest first
  EXPECT_EQ(coarsest.at("pattern"), "phase_col");
  EXPECT_EQ(coarsest.at("level"), 2);
  const cv::Mat image = cv::imread((out / coarsest.at("file").get<std::string>()).string(), cv::IMREAD_GRAYSCALE);
  for (int x = 0; x < image.cols; ++x) {
    EXPECT_NEAR(image.at<unsigned char>(0, x), 127.5 + 127.5 * std::cos(2.0 * kPi * x / 96.0), 0.5) << x;
  }
  // A manifest with a level beyond the axis's periods is refused, naming the frame.
  manifest["frames"][2]["level"] = 3;
  std::ofstream(out / "manifest.json") << manifest.dump(2);
  const auto refused = testing::run_cli("check " + out.string());
  EXPECT_NE(refused.exit_code, 0) << refused.output;
  EXPECT_NE(refused.output.find("level 3 outside 0 to 2"), std::string::npos) << refused.output;
}

struct Errors {
  double rms_px = 0.0;
  std::size_t pixels = 0;
};

// Column correspondence errors against the truth over the pixels both transports decode (errors over 2 px, decoding
// failures rather than precision, counted apart).
std::pair<Errors, Errors> same_pixel_errors(const fs::path& a, const fs::path& b, const fs::path& truth_dir,
                                            std::size_t& outliers) {
  const CompressedTransport ta = read_transport(a), tb = read_transport(b);
  const cv::Mat truth = cv::imread((truth_dir / "correspondences.tiff").string(), cv::IMREAD_UNCHANGED);
  Errors ea, eb;
  outliers = 0;
  for (std::size_t c = 0; c < ta.camera_pixels(); ++c) {
    const cv::Vec3f seen = truth.at<cv::Vec3f>(static_cast<int>(c / truth.cols), static_cast<int>(c % truth.cols));
    if (std::isnan(seen[0]) || (ta.flags[c] & kFlagValid) == 0 || (tb.flags[c] & kFlagValid) == 0) continue;
    const double da = ta.correspondence[2 * c] - seen[0], db = tb.correspondence[2 * c] - seen[0];
    if (std::abs(da) > 2.0 || std::abs(db) > 2.0) {
      ++outliers;
      continue;
    }
    ea.rms_px += da * da;
    eb.rms_px += db * db;
    ++ea.pixels;
  }
  eb.pixels = ea.pixels;
  ea.rms_px = std::sqrt(ea.rms_px / std::max<std::size_t>(ea.pixels, 1));
  eb.rms_px = std::sqrt(eb.rms_px / std::max<std::size_t>(eb.pixels, 1));
  return {ea, eb};
}

// Renders scene_file with the family's options and a noise seed into `out`, and decodes its T into out/T.h5.
void render_and_decode(const fs::path& scene_file, const std::string& options, int seed, const fs::path& out) {
  const auto simulated = testing::run_cli("-q simulate --scene " + scene_file.string() + " " + options + " --seed " +
                                          std::to_string(seed) + " -o " + out.string());
  ASSERT_EQ(simulated.exit_code, 0) << simulated.output;
  const auto decoded =
      testing::run_cli("-q transport " + (out / "capture").string() + " -o " + (out / "T.h5").string());
  ASSERT_EQ(decoded.exit_code, 0) << decoded.output;
}

// A copy of base's scene.json with the projector defocused by a Gaussian of sigma `defocus` projector pixels.
fs::path defocused_scene(const fs::path& base, const fs::path& dir, const std::string& name, double defocus) {
  nlohmann::json scene;
  std::ifstream(base / "scene.json") >> scene;
  scene["render"]["projector_defocus_px"] = defocus;
  const fs::path scene_file = dir / (name + std::to_string(defocus) + ".json");
  std::ofstream(scene_file) << scene.dump(2);
  return scene_file;
}

TEST(PhaseFamilyTest, SubPixelInFocusAndBeatsGrayCodeUnderDefocus) {
  testing::TempDir dir("phase_family");
  const fs::path base = dir.path() / "base";
  const std::string size = " --camera 160x128 --projector 128x80";
  ASSERT_EQ(
      testing::run_cli("-q simulate --scene plane-lambert --dot-spacing 0" + size + " -o " + base.string()).exit_code,
      0);
  for (const double defocus : {0.0, 2.5}) {
    const fs::path scene_file = defocused_scene(base, dir.path(), "scene_", defocus);
    fs::path transports[3];
    const std::string families[3] = {"--family graycode", "--family phase", "--family phase --phase-ratio 4"};
    for (int f = 0; f < 3; ++f) {
      const fs::path out = dir.path() / (std::to_string(f) + "_" + std::to_string(defocus));
      const auto simulated = testing::run_cli("-q simulate --scene " + scene_file.string() + " " + families[f] +
                                              " --dot-spacing 0 -o " + out.string());
      ASSERT_EQ(simulated.exit_code, 0) << simulated.output;
      const auto decoded =
          testing::run_cli("-q transport " + (out / "capture").string() + " -o " + (out / "T.h5").string());
      ASSERT_EQ(decoded.exit_code, 0) << decoded.output;
      transports[f] = out / "T.h5";
    }
    const fs::path truth = dir.path() / ("0_" + std::to_string(defocus)) / "truth";
    for (const int f : {1, 2}) {
      std::size_t outliers = 0;
      const auto [gray, phase] = same_pixel_errors(transports[0], transports[f], truth, outliers);
      std::printf("defocus %.1f px: %zu pixels, column RMS Gray %.4f px, %s %.4f px, %zu over 2 px\n", defocus,
                  gray.pixels, gray.rms_px, families[f].c_str(), phase.rms_px, outliers);
      EXPECT_GT(gray.pixels, defocus == 0.0 ? 160U * 128U / 3 : 160U * 128U / 4);
      if (defocus == 0.0) {
        EXPECT_LT(phase.rms_px, 0.1) << families[f];
      } else {
        EXPECT_LT(phase.rms_px, 0.5 * gray.rms_px) << families[f];
      }
    }
  }
}

// The plane decoded from `other` (a capture of the 160 x 128 camera and 128 x 80 projector, out/T.h5) against the
// truth, on the pixels that `ours` (the order code's, same scene) decodes too: a third of the camera at least, within
// 0.1 projector pixel RMS (column), under 1 % of them over 2 px.
void expect_as_precise_as_ours(const fs::path& ours, const fs::path& other, const std::string& what) {
  std::size_t outliers = 0;
  const auto [our_errors, errors] = same_pixel_errors(ours / "T.h5", other / "T.h5", ours / "truth", outliers);
  std::printf("%s: %zu pixels, column RMS order code %.4f px, %s %.4f px, %zu over 2 px\n", what.c_str(),
              our_errors.pixels, our_errors.rms_px, what.c_str(), errors.rms_px, outliers);
  EXPECT_GT(our_errors.pixels, 160U * 128U / 3);
  EXPECT_LT(errors.rms_px, 0.1) << what;
  EXPECT_LT(outliers, our_errors.pixels / 100) << what;
}

// Another tool's capture, described by its manifest: sines rather than cosines shifting the other way (origin 270
// degrees, reversed: 0.5 + 0.5 sin(2 pi x / P + 2 pi k / N), as many tools write them), an order code of whole
// periods without inverses, files of its own names in its own order. Decoded with those conventions it is as precise
// as ours on the same pixels, which is the proof they are used: the same frames read with our conventions are not.
TEST(PhaseFamilyTest, AnotherToolsCaptureIsReadFromItsManifest) {
  testing::TempDir dir("phase_foreign");
  const std::string scene = " --scene plane-lambert --dot-spacing 0 --camera 160x128 --projector 128x80";
  const fs::path ours = dir.path() / "ours", theirs = dir.path() / "theirs";
  ASSERT_EQ(testing::run_cli("-q simulate" + scene + " --family phase -o " + ours.string()).exit_code, 0);
  ASSERT_EQ(testing::run_cli("-q simulate" + scene +
                             " --family phase --phase-origin 270 --phase-reversed 1 --order-unit 2 "
                             "--order-inverses 0 -o " +
                             theirs.string())
                .exit_code,
            0);
  const fs::path capture = theirs / "capture";
  nlohmann::json manifest;
  std::ifstream(capture / "manifest.json") >> manifest;
  // Columns: ceil(log2(ceil(128 / 16))) = 3 order bits of whole periods, no inverses; rows ceil(log2(5)) = 3.
  std::size_t order_frames = 0;
  for (const auto& frame : manifest.at("frames")) {
    order_frames += frame.at("pattern").get<std::string>().rfind("order_", 0) == 0 ? 1 : 0;
  }
  EXPECT_EQ(order_frames, 6U);
  nlohmann::json frames = nlohmann::json::array();
  for (std::size_t i = manifest.at("frames").size(); i-- > 0;) {
    nlohmann::json frame = manifest.at("frames").at(i);
    const std::string renamed = "img_" + std::to_string(frames.size()) + ".png";
    fs::rename(capture / frame.at("file").get<std::string>(), capture / renamed);
    frame["file"] = renamed;
    frame.erase("inverse");
    frames.push_back(frame);
  }
  manifest["frames"] = frames;
  std::ofstream(capture / "manifest.json") << manifest.dump(2);
  const auto patterns = testing::run_cli(
      "-q patterns --family phase --phase-origin 270 --phase-reversed 1 "
      "--projector 64x40 -o " +
      (dir.path() / "patterns").string());
  ASSERT_EQ(patterns.exit_code, 0) << patterns.output;
  nlohmann::json projected;
  std::ifstream(dir.path() / "patterns" / "manifest.json") >> projected;
  for (const auto& frame : projected.at("frames")) {
    if (frame.at("pattern") != "phase_col" || frame.at("step") != 1) continue;
    const cv::Mat image =
        cv::imread((dir.path() / "patterns" / frame.at("file").get<std::string>()).string(), cv::IMREAD_GRAYSCALE);
    for (int x = 0; x < image.cols; ++x) {  // step 1 of 4: 0.5 + 0.5 sin(2 pi x / 16 + pi / 2)
      EXPECT_NEAR(image.at<unsigned char>(0, x), 127.5 + 127.5 * std::sin(2.0 * kPi * x / 16.0 + 0.5 * kPi), 0.501);
    }
  }

  for (const fs::path& out : {ours, theirs}) {
    const auto decoded =
        testing::run_cli("-q transport " + (out / "capture").string() + " -o " + (out / "T.h5").string());
    ASSERT_EQ(decoded.exit_code, 0) << decoded.output;
  }
  expect_as_precise_as_ours(ours, theirs, "another tool's conventions");  // whole periods: a few edge pixels missed
  std::size_t outliers = 0;

  // The same frames with the conventions taken out of the manifest decode wrong (or not at all).
  for (const char* convention : {"phase_origin", "phase_reversed"}) {
    nlohmann::json stripped = manifest;
    stripped["parameters"].erase(convention);
    std::ofstream(capture / "manifest.json") << stripped.dump(2);
    const fs::path wrong = dir.path() / (std::string("without_") + convention + ".h5");
    const auto decoded = testing::run_cli("-q transport " + capture.string() + " -o " + wrong.string());
    ASSERT_EQ(decoded.exit_code, 0) << decoded.output;
    const auto [ours_again, misread] = same_pixel_errors(ours / "T.h5", wrong, ours / "truth", outliers);
    std::printf("without %s: %zu pixels, column RMS %.4f px, %zu over 2 px\n", convention, ours_again.pixels,
                misread.rms_px, outliers);
    EXPECT_GT(misread.rms_px + static_cast<double>(outliers) / std::max<std::size_t>(ours_again.pixels, 1), 0.2)
        << "without " << convention;
  }
}

// Heterodyne unwrapping on the synthetic rig: 20, 16 and 13 fringes across each axis (periods 6.4, 8 and 9.8 columns,
// 4, 5 and 6.2 rows of a 128 x 80 projector), no order code, decoded within 0.1 projector pixel RMS of the truth on the
// plane, as the order code's capture is, on the same pixels.
TEST(PhaseFamilyTest, HeterodyneBeatsUnwrapOnTheRig) {
  testing::TempDir dir("phase_heterodyne");
  const std::string options = "--family phase --dot-spacing 0 --camera 160x128 --projector 128x80";
  const fs::path ours = dir.path() / "ours", beats = dir.path() / "beats";
  render_and_decode("plane-lambert", options, 1, ours);
  render_and_decode("plane-lambert", options + " --phase-fringes 20 --phase-heterodyne 4", 1, beats);
  nlohmann::json manifest;
  std::ifstream(beats / "capture" / "manifest.json") >> manifest;
  std::size_t steps = 0;
  int deepest = 0;
  for (const auto& frame : manifest.at("frames")) {
    EXPECT_NE(frame.at("pattern").get<std::string>().rfind("order_", 0), 0U) << "no order code with beats";
    if (frame.at("pattern") != "phase_col" && frame.at("pattern") != "phase_row") continue;
    ++steps;
    deepest = std::max(deepest, frame.value("level", 0));
  }
  EXPECT_EQ(steps, 2U * 3U * 4U);  // two axes, three fringe counts, four steps
  EXPECT_EQ(deepest, 2);
  expect_as_precise_as_ours(ours, beats, "heterodyne 20/16/13");
  // B too large for F: refused before anything is written, naming the parameters.
  const auto refused = testing::run_cli(
      "patterns --family phase --phase-fringes 8 --phase-heterodyne 5 --projector "
      "128x80 -o " +
      (dir.path() / "refused").string());
  EXPECT_EQ(refused.exit_code, 3) << refused.output;
  EXPECT_NE(refused.output.find("phase_heterodyne 5 on 8 fringes"), std::string::npos) << refused.output;
  EXPECT_FALSE(fs::exists(dir.path() / "refused"));
}

// The object's coverage (%) and depth RMS (mm) of a reconstruction, on the pixels `others` reconstruct too (all of its
// own for none).
std::pair<double, double> evaluated(const fs::path& reconstruction, const fs::path& truth, const std::string& others) {
  const auto run = testing::run_cli("-q evaluate " + reconstruction.string() + " --truth " + truth.string() +
                                    " --force" + (others.empty() ? "" : " --same-pixels-as " + others));
  EXPECT_EQ(run.exit_code, 0) << run.output;
  nlohmann::json report;
  std::ifstream(reconstruction / "evaluation.json") >> report;
  const auto& object = report.at("object_pixels");
  const auto& rms = object.at("depth_error_mm").at("rms");
  return {object.at("coverage_percent").get<double>(), rms.is_null() ? NAN : rms.get<double>()};
}

// A dot grid after the phases gives T's full rows, so the integration and the fusion run on a phase capture, seeded
// by the phases' correspondences: on the plane the fusion covers most of it and is several times as accurate as the
// triangulation alone on the same pixels.
TEST(PhaseFamilyTest, DotGridAfterThePhasesFeedsTheIntegrationAndFusion) {
  testing::TempDir dir("phase_dots");
  const fs::path out = dir.path() / "plane";
  ASSERT_EQ(testing::run_cli("-q simulate --scene plane-lambert --family phase --dot-spacing 4 --camera 160x128 "
                             "--projector 128x80 -o " +
                             out.string())
                .exit_code,
            0);
  nlohmann::json manifest;
  std::ifstream(out / "capture" / "manifest.json") >> manifest;
  ASSERT_EQ(manifest.at("frames").back().at("pattern"), "dot");
  EXPECT_EQ(manifest.at("frames").back().at("dot_offset"), nlohmann::json::array({3, 3}));
  const auto decoded =
      testing::run_cli("-q transport " + (out / "capture").string() + " -o " + (out / "T.h5").string());
  ASSERT_EQ(decoded.exit_code, 0) << decoded.output;
  const CompressedTransport t = read_transport(out / "T.h5");
  EXPECT_EQ(t.protocol(), "phase+dots");
  for (const std::string method : {"triangulate", "fused"}) {
    const auto run = testing::run_cli("-q reconstruct " + (out / "T.h5").string() + " --calib " +
                                      (out / "truth" / "rig.yaml").string() + " --method " + method + " -o " +
                                      (out / method).string());
    ASSERT_EQ(run.exit_code, 0) << run.output;
  }
  const std::string both = (out / "triangulate").string() + " " + (out / "fused").string();
  const auto [coverage, fused_mm] = evaluated(out / "fused", out, both);
  const auto [same, triangulated_mm] = evaluated(out / "triangulate", out, both);
  std::printf("phase + dots on the plane: %.1f %% covered, depth RMS fused %.4f mm, triangulated %.4f mm\n", coverage,
              fused_mm, triangulated_mm);
  EXPECT_GT(coverage, 60.0);
  EXPECT_EQ(coverage, same);
  EXPECT_LT(fused_mm, 0.2);  // 0.05 % of the 400 mm plane
  EXPECT_LT(fused_mm, 0.3 * triangulated_mm);
}

// The table of docs/accuracy.md ("Phase shifting"): Gray code, phase shifting unwrapped by the order code and by longer
// periods (ratio 4) on the same renderings of the cube and the board, in focus and defocused, over three noise seeds;
// correspondence (column) and triangulated depth RMS on the pixels all three decode (the phase families alone where
// Gray code reconstructs nothing). Run by hand:
// phase_family_test --gtest_also_run_disabled_tests --gtest_filter='*.DISABLED_TableOf*'.
TEST(PhaseFamilyTest, DISABLED_TableOfCubeAndBoardOverSeeds) {
  testing::TempDir dir("phase_table");
  const std::string families[3] = {"--family graycode", "--family phase", "--family phase --phase-ratio 4"};
  std::printf(
      "| scene | defocus (px) | seed | coverage Gray / order / periods (%%) | compared | column RMS Gray / order / "
      "periods (px) | depth RMS Gray / order / periods (mm) |\n");
  for (const std::string name : {"cube-anisotropic", "board-plane"}) {
    const fs::path base = dir.path() / name;
    ASSERT_EQ(testing::run_cli("-q simulate --scene " + name + " --dot-spacing 0 -o " + base.string()).exit_code, 0);
    for (const double defocus : {0.0, 2.5, 4.0}) {
      const fs::path scene_file = defocused_scene(base, dir.path(), name, defocus);
      for (const int seed : {1, 2, 3}) {
        fs::path out[3];
        cv::Mat depth[3];
        for (const int f : {0, 1, 2}) {
          out[f] = dir.path() / (name + std::to_string(defocus) + std::to_string(seed) + "_" + std::to_string(f));
          ASSERT_NO_FATAL_FAILURE(render_and_decode(scene_file, families[f] + " --dot-spacing 0", seed, out[f]));
          const auto reconstructed = testing::run_cli("-q reconstruct " + (out[f] / "T.h5").string() + " --calib " +
                                                      (out[f] / "truth" / "rig.yaml").string() +
                                                      " --method triangulate -o " + (out[f] / "rec").string());
          // Exit 6: nothing decoded to reconstruct (a family the defocus defeats), no depth.
          ASSERT_TRUE(reconstructed.exit_code == 0 || reconstructed.exit_code == 6) << reconstructed.output;
          depth[f] = reconstructed.exit_code == 0
                         ? cv::imread((out[f] / "rec" / "depth.tiff").string(), cv::IMREAD_UNCHANGED)
                         : cv::Mat(cv::Size(1, 1), CV_32F, cv::Scalar(NAN));
        }
        // Errors on the pixels every compared family decodes (all three but where the defocus defeats Gray code, which
        // then reconstructs nothing or a few pixels), columns against the true correspondences, depths against the
        // true depth.
        const cv::Mat truth = cv::imread((out[0] / "truth" / "depth.tiff").string(), cv::IMREAD_UNCHANGED);
        bool compared[3];  // reconstructs at least 1 % of the pixels with a true depth
        for (int f = 0; f < 3; ++f) {
          const cv::Mat has_truth = truth > 0.0f;
          compared[f] = depth[f].total() > 1 &&
                        cv::countNonZero(has_truth & (depth[f] == depth[f])) >= 0.01 * cv::countNonZero(has_truth);
        }
        const CompressedTransport t[3] = {read_transport(out[0] / "T.h5"), read_transport(out[1] / "T.h5"),
                                          read_transport(out[2] / "T.h5")};
        const cv::Mat seen = cv::imread((out[0] / "truth" / "correspondences.tiff").string(), cv::IMREAD_UNCHANGED);
        double column[3] = {0, 0, 0}, z[3] = {0, 0, 0};
        std::size_t columns = 0, both = 0, covered[3] = {0, 0, 0}, object = 0;
        for (std::size_t c = 0; c < truth.total(); ++c) {
          const int i = static_cast<int>(c);
          const float zt = truth.at<float>(i);
          if (zt > 0.0f) {
            ++object;
            bool all = true;
            for (int f = 0; f < 3; ++f) {
              const bool has = depth[f].total() > 1 && !std::isnan(depth[f].at<float>(i));
              covered[f] += has ? 1 : 0;
              all = all && (has || !compared[f]);  // coverage counts every family, the errors the compared
            }
            if (all) {
              ++both;
              for (int f = 0; f < 3; ++f) z[f] += compared[f] ? std::pow(depth[f].at<float>(i) - zt, 2) : 0.0;
            }
          }
          const float u = seen.at<cv::Vec3f>(i)[0];
          bool valid = !std::isnan(u);
          double d[3] = {0, 0, 0};
          for (int f = 0; f < 3; ++f) {
            if (!compared[f]) continue;
            valid = valid && (t[f].flags[c] & kFlagValid) != 0;
            d[f] = t[f].correspondence[2 * c] - u;
          }
          if (!valid || std::abs(d[0]) > 2.0 || std::abs(d[1]) > 2.0 || std::abs(d[2]) > 2.0) continue;
          ++columns;
          for (int f = 0; f < 3; ++f) column[f] += d[f] * d[f];
        }
        const auto rms = [&](const double* sums, std::size_t n) {
          std::string text;
          for (int f = 0; f < 3; ++f) {
            char value[32];
            std::snprintf(value, sizeof value, "%.4f", std::sqrt(sums[f] / static_cast<double>(n)));
            text += (f > 0 ? " / " : "") + std::string(compared[f] && n > 0 ? value : "-");
          }
          return text;
        };
        std::printf("| %s | %.1f | %d | %.1f / %.1f / %.1f | %zu | %s | %s |\n", name.c_str(), defocus, seed,
                    100.0 * covered[0] / object, 100.0 * covered[1] / object, 100.0 * covered[2] / object, both,
                    rms(column, columns).c_str(), rms(z, both).c_str());
        std::fflush(stdout);
      }
    }
  }
}

// The table of docs/accuracy.md ("Phase shifting with the dot grid"): Gray code and phase shifting, each followed by
// the dot grid of spacing 8, on the same renderings of the cube and the board, in focus and slightly defocused, over
// three noise seeds; per depth method, each family's coverage and both families' depth RMS on the pixels both
// reconstruct. Run by hand: phase_family_test --gtest_also_run_disabled_tests --gtest_filter='*DotGridTable*'.
TEST(PhaseFamilyTest, DISABLED_DotGridTableOfCubeAndBoardOverSeeds) {
  testing::TempDir dir("phase_dots_table");
  const std::string families[2] = {"graycode", "phase"};
  const std::string methods[3] = {"triangulate", "integrate", "fused"};
  std::printf(
      "| scene | defocus (px) | seed | method | coverage Gray / phase (%%) | both (%%) | depth RMS Gray / phase "
      "(mm) |\n");
  for (const std::string name : {"cube-anisotropic", "board-plane"}) {
    const fs::path base = dir.path() / name;
    ASSERT_EQ(testing::run_cli("-q simulate --scene " + name + " --dot-spacing 0 -o " + base.string()).exit_code, 0);
    for (const double defocus : {0.0, 1.0, 1.5}) {
      const fs::path scene_file = defocused_scene(base, dir.path(), name, defocus);
      for (const int seed : {1, 2, 3}) {
        fs::path out[2];
        for (const int f : {0, 1}) {
          out[f] = dir.path() / (name + std::to_string(defocus) + std::to_string(seed) + families[f]);
          ASSERT_NO_FATAL_FAILURE(
              render_and_decode(scene_file, "--family " + families[f] + " --dot-spacing 8", seed, out[f]));
          for (const auto& method : methods) {
            const auto run = testing::run_cli("-q reconstruct " + (out[f] / "T.h5").string() + " --calib " +
                                              (out[f] / "truth" / "rig.yaml").string() + " --method " + method +
                                              " -o " + (out[f] / method).string());
            ASSERT_TRUE(run.exit_code == 0 || run.exit_code == 6) << run.output;  // 6: nothing reconstructed
          }
        }
        for (const auto& method : methods) {
          double alone[2] = {0, 0}, rms[2] = {NAN, NAN}, both = 0.0;
          for (const int f : {0, 1}) {
            if (!fs::exists(out[f] / method / "depth.tiff")) continue;
            alone[f] = evaluated(out[f] / method, out[f], "").first;
            if (!fs::exists(out[1 - f] / method / "depth.tiff")) continue;
            std::tie(both, rms[f]) = evaluated(out[f] / method, out[f], (out[1 - f] / method).string());
          }
          std::printf("| %s | %.1f | %d | %s | %.1f / %.1f | %.1f | %.3f / %.3f |\n", name.c_str(), defocus, seed,
                      method.c_str(), alone[0], alone[1], both, rms[0], rms[1]);
          std::fflush(stdout);
        }
      }
    }
  }
}

}  // namespace
}  // namespace rfrecon::transport
