// The capture run: pattern by pattern, show, wait out the latency, grab each exposure, check, write.
#include "host/acquire/capture_run.h"

#include <algorithm>
#include <cstdio>
#include <optional>

#include <spdlog/spdlog.h>

#include "host/acquire/frame_checks.h"
#include "host/acquire/hdr_merge.h"
#include "host/acquire/latency.h"
#include "host/capture/graycode_patterns.h"
#include "host/capture/pattern_files.h"
#include "host/core/atomic_file.h"
#include "host/core/errors.h"
#include "host/core/image_file.h"
#include "host/core/progress.h"

namespace rfrecon::acquire {

namespace fs = std::filesystem;

namespace {

std::string size_words(cv::Size size) { return std::to_string(size.width) + "x" + std::to_string(size.height); }

// The protocol's projector size, checked against the display's.
cv::Size protocol_size(const Projector& projector, const CaptureRunOptions& options) {
  const cv::Size display = projector.size();
  const cv::Size wanted = options.protocol.projector_size.empty() ? display : options.protocol.projector_size;
  if (wanted.width > display.width || wanted.height > display.height) {
    throw UsageError(projector.name() + " is " + size_words(display) + ", smaller than the projector size " +
                     size_words(wanted) +
                     ": patterns are shown pixel for pixel, never scaled; set the display to the "
                     "projector's native resolution");
  }
  if (wanted != display) {
    spdlog::warn("capture: patterns of {} shown in the top-left corner of {} ({}); the rest stays black",
                 size_words(wanted), projector.name(), size_words(display));
  }
  return wanted;
}

// The manifest of the camera's raw frames (for linearising them) and of the files the run writes.
capture::CaptureManifest scan_manifest(const Camera& camera, const CaptureRunOptions& options, cv::Size projector) {
  const CameraFormat format = camera.format();
  capture::CaptureManifest manifest;
  manifest.family = options.protocol.family;
  manifest.parameters = options.protocol.parameters;
  manifest.projector_size = projector;
  manifest.camera_size = format.size;
  manifest.dot_spacing = options.protocol.dot_spacing;
  manifest.bit_depth = format.bit_depth;
  manifest.black_level = options.black_level_dn.value_or(format.black_level_dn);
  manifest.camera_response = options.camera_response;
  manifest.frames =
      capture::protocol_frames(capture::protocol_options(manifest), options.format == "tiff" ? ".tiff" : ".png");
  capture::validate_manifest(manifest, "capture of " + camera.name());
  return manifest;
}

std::string pattern_words(const capture::Pattern& pattern) {
  std::string words = pattern.kind;
  if (pattern.bit >= 0) words += " bit " + std::to_string(pattern.bit) + (pattern.inverse ? " inverse" : "");
  return words;
}

// Captures the frames of one scan, pattern by pattern, with the checks that catch dropped and late frames.
class ScanRecorder {
 public:
  ScanRecorder(Projector& projector, Camera& camera, const CaptureRunOptions& options, int latency_frames,
               capture::CaptureManifest camera_manifest)
      : projector_(projector),
        camera_(camera),
        options_(options),
        latency_frames_(latency_frames),
        camera_manifest_(std::move(camera_manifest)),
        files_manifest_(camera_manifest_) {
    if (options.exposures_us.size() > 1) set_merged_format(files_manifest_);
  }

  CaptureRunReport record(const fs::path& dir) {
    grabs_ = 0;
    repeated_ = 0;
    CaptureRunReport report;
    report.latency_frames = latency_frames_;
    report.manifest = files_manifest_;
    const bool known = std::all_of(exposures_.begin(), exposures_.end(), [](double e) { return e > 0.0; });
    if (known) report.manifest.exposures_us = exposures_;
    capture::CaptureChecks checks(report.manifest);
    Progress progress("capture", report.manifest.frames.size(), "frames");
    cv::Mat white, black;  // linear
    const auto& frames = report.manifest.frames;
    std::vector<cv::Mat> pair(2);  // a Gray pattern's frame and its inverse's: written once they add up
    for (std::size_t i = 0; i < frames.size(); ++i) {
      const auto& pattern = frames[i].pattern;
      cv::Mat frame = capture_pattern(pattern);
      if (pattern.kind == capture::pattern_kind::kWhite) white = linear(frame);
      if (pattern.kind == capture::pattern_kind::kBlack) {
        black = linear(frame);
        check_white_over_black(white, black);
      }
      const bool gray = capture::is_gray(pattern);
      if (gray && !pattern.inverse) {
        pair[0] = frame;
        continue;
      }
      const std::size_t first = gray ? i - 1 : i;
      if (gray) {
        pair[1] = frame;
        report.recaptured_pairs += recapture_until_pair_adds_up(frames, first, pair, white, black);
      }
      for (std::size_t k = first; k <= i; ++k) {
        const cv::Mat& done = gray ? pair[k - first] : frame;
        write_image(dir / frames[k].file, done);
        checks.add(k, done);
        progress.advance();
      }
    }
    capture::write_manifest(report.manifest, dir);
    report.checks = checks.finish();
    for (const auto& finding : report.checks.findings) spdlog::warn("capture: {}", finding.message);
    report.grabs = grabs_;
    report.repeated_frames = repeated_;
    return report;
  }

  // Locks the camera at each exposure of the options in turn (the camera's own when none), keeping what it applied.
  void prepare_exposures() {
    exposures_.clear();
    if (options_.exposures_us.empty()) exposures_.push_back(camera_.lock_exposure(0.0));
    for (double exposure : options_.exposures_us) exposures_.push_back(camera_.lock_exposure(exposure));
  }

 private:
  void check_white_over_black(const cv::Mat& white, const cv::Mat& black) const {
    const double share = lit_share(white, black);
    if (share < 0.001) {
      throw HardwareError(camera_.name() + ": only " + std::to_string(100.0 * share) +
                          " % of the pixels are brighter " +
                          "in the white frame than in the black one (by 4 % of full scale, unsaturated): the camera " +
                          "does not see " + projector_.name() + ", the exposure is too short or too long, or frames " +
                          "are shown late (measure the latency: --measure-latency)");
    }
  }

  cv::Mat linear(const cv::Mat& frame) const {
    return capture::linearize_frame(frame, files_manifest_, camera_.name() + " frame");
  }

  // Captures the Gray pair of frames `first` and first + 1 (`pair`) again while its frames do not add up to
  // white + black; returns how many times it did.
  std::size_t recapture_until_pair_adds_up(const std::vector<capture::Frame>& frames, std::size_t first,
                                           std::vector<cv::Mat>& pair, const cv::Mat& white, const cv::Mat& black) {
    for (int attempt = 0;; ++attempt) {
      const double share = pair_mismatch_share(white, black, linear(pair[0]), linear(pair[1]));
      if (!(share > kMaxPairMismatchShare)) return static_cast<std::size_t>(attempt);
      const std::string what = pattern_words(frames[first].pattern) + " and its inverse add up to white + black on " +
                               "only " + std::to_string(100.0 * (1.0 - share)) + " % of lit pixels";
      if (attempt >= options_.retries) {
        throw HardwareError(camera_.name() + ": " + what + " after " + std::to_string(attempt + 1) +
                            " captures: frames are dropped or shown late; measure the latency again "
                            "(--measure-latency), close other programs that draw on the display, or give "
                            "--latency-frames one more than measured");
      }
      spdlog::warn("capture: {} (a dropped or late frame); capturing the pair again", what);
      pair[0] = capture_pattern(frames[first].pattern);
      pair[1] = capture_pattern(frames[first + 1].pattern);
    }
  }

  // The frame of one pattern: raw, or merged from every exposure.
  cv::Mat capture_pattern(const capture::Pattern& pattern) {
    if (options_.before_pattern) options_.before_pattern();
    cv::Mat image(projector_.size(), CV_8UC1, cv::Scalar(0));
    const cv::Size size = camera_manifest_.projector_size;
    capture::render_pattern(pattern, capture::protocol_options(camera_manifest_)).copyTo(image(cv::Rect({0, 0}, size)));
    projector_.show(image);
    if (options_.exposures_us.size() <= 1) return fresh_frame(pattern);
    std::vector<cv::Mat> raw;
    for (double exposure : options_.exposures_us) {
      camera_.lock_exposure(exposure);
      raw.push_back(fresh_frame(pattern));
    }
    return merge_exposures(raw, exposures_, camera_manifest_);
  }

  // A frame grabbed after the latency's frames are discarded, taken again while it repeats the one before: a
  // repeated buffer, or a display later than measured (a noise-free camera, such as a screen grab, sees the previous
  // pattern unchanged). Gives up after `retries` + 1 latencies' worth of grabs.
  cv::Mat fresh_frame(const capture::Pattern& pattern) {
    for (int i = 0; i < latency_frames_; ++i) grab();
    const int attempts = (options_.retries + 1) * (latency_frames_ + 1);
    for (int attempt = 1;; ++attempt) {
      const cv::Mat frame = grab();
      if (last_.empty() || !same_frame(frame, last_)) {
        last_ = frame.clone();  // the camera may reuse its buffer for the next frame
        return last_;
      }
      ++repeated_;
      if (attempt >= attempts) {
        throw HardwareError(camera_.name() + " handed back the same frame " + std::to_string(attempt + 1) + " times (" +
                            pattern_words(pattern) + "): its stream repeats buffers, or the display " +
                            "stopped; check the camera's frame rate and trigger settings");
      }
      spdlog::warn("capture: {} repeated a frame ({}): a dropped or late frame; grabbing again", camera_.name(),
                   pattern_words(pattern));
    }
  }

  cv::Mat grab() {
    ++grabs_;
    cv::Mat frame = camera_.grab(options_.timeout);
    capture::check_raw_frame(frame, camera_manifest_, camera_.name() + " frame " + std::to_string(grabs_));
    return frame;
  }

  Projector& projector_;
  Camera& camera_;
  const CaptureRunOptions& options_;
  int latency_frames_;
  capture::CaptureManifest camera_manifest_;  // the camera's raw frames
  capture::CaptureManifest files_manifest_;   // the frames written: raw, or merged (HDR)
  std::vector<double> exposures_;
  cv::Mat last_;
  std::size_t grabs_ = 0;
  std::size_t repeated_ = 0;
};

ScanRecorder make_recorder(Projector& projector, Camera& camera, const CaptureRunOptions& options) {
  if (options.format != "png" && options.format != "tiff") {
    throw UsageError("capture format must be png or tiff, got '" + options.format + "'");
  }
  for (double exposure : options.exposures_us) {
    if (!(exposure > 0.0)) throw UsageError("exposures must be positive microseconds");
  }
  auto manifest = scan_manifest(camera, options, protocol_size(projector, options));
  const int latency =
      options.latency_frames >= 0 ? options.latency_frames : measure_latency(projector, camera, options);
  return ScanRecorder(projector, camera, options, latency, std::move(manifest));
}

}  // namespace

int measure_latency(Projector& projector, Camera& camera, const CaptureRunOptions& options) {
  const auto& exposures = options.exposures_us;
  camera.lock_exposure(exposures.empty() ? 0.0 : *std::max_element(exposures.begin(), exposures.end()));
  LatencyOptions latency;
  latency.timeout = options.timeout;
  const int frames = measure_latency_frames(projector, camera, latency);
  spdlog::info("capture: {} sees a pattern {} frame(s) after {} shows it", camera.name(), frames, projector.name());
  return frames;
}

CaptureRunReport capture_scan(Projector& projector, Camera& camera, const CaptureRunOptions& options,
                              const fs::path& out_dir, bool force) {
  StagingDirectory staging(out_dir, force);
  ScanRecorder recorder = make_recorder(projector, camera, options);
  recorder.prepare_exposures();
  auto report = recorder.record(staging.path());
  staging.commit();
  return report;
}

std::vector<CaptureRunReport> capture_poses(Projector& projector, Camera& camera, const CaptureRunOptions& options,
                                            int poses, const std::function<void(int pose)>& before_pose,
                                            const fs::path& out_dir, bool force) {
  if (poses < 1) throw UsageError("--poses must be at least 1");
  StagingDirectory staging(out_dir, force);
  ScanRecorder recorder = make_recorder(projector, camera, options);
  std::vector<CaptureRunReport> reports;
  for (int pose = 0; pose < poses; ++pose) {
    before_pose(pose);
    recorder.prepare_exposures();
    char name[32];
    std::snprintf(name, sizeof name, "pose_%02d", pose + 1);
    fs::create_directories(staging.path() / name);
    spdlog::info("capture: pose {} of {}", pose + 1, poses);
    reports.push_back(recorder.record(staging.path() / name));
  }
  staging.commit();
  return reports;
}

}  // namespace rfrecon::acquire
